#pragma once

#include <functional>
#include <string>

#include "core/util/status.h"
#include "storage/set_cache.h"

namespace alignset::server {

// A read-only replica's --fill-from: asks the writer at `address` for a
// canonical set (GetAlignedSet for the key's own canonical directions, so
// the answer needs no alignment) and checks that the writer served exactly
// that key: the same N, directions, realization and profile (a writer with
// other optimization settings has another profile: FAILED_PRECONDITION), no
// swap or inversion, and N points. `token` (may be empty) is sent as the
// bearer token; `timeout_seconds` bounds one call (the writer may have to
// optimize the set first). `cancelled` is asked every 50 ms while the call
// is in flight: true cancels it (the writer sees its caller leave and drops
// the job when no one else waits) and the fill returns CANCELLED.
using FillCancelled = std::function<bool()>;
using FillFunction = std::function<StatusOr<storage::SetRecord>(const storage::SetKey&, const FillCancelled&)>;
// With `tls_ca_pem` (a PEM root certificate, not a path) the channel speaks
// TLS and checks the writer's certificate for `tls_name` (empty: the host of
// `address`); without it, plaintext.
FillFunction MakeWriterFill(const std::string& address, const std::string& token, double timeout_seconds,
                            const std::string& tls_ca_pem = "", const std::string& tls_name = "");

}  // namespace alignset::server
