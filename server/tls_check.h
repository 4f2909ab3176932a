#pragma once

#include <string>

#include "core/util/status.h"

namespace alignset::server {

// Checks what gRPC would only report as "cannot listen": that `cert_pem`
// holds a certificate, `key_pem` a private key, and that the key belongs to
// the certificate (the first one of a chain). The paths name the files in
// the messages.
Status CheckTlsKeyPair(const std::string& cert_pem, const std::string& key_pem,
                       const std::string& cert_path, const std::string& key_path);

}  // namespace alignset::server
