#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace alignset::server {

// A client-supplied string made safe for a log line or an error message:
// quoted, printable ASCII kept, everything else (newlines, control bytes,
// quotes, backslashes, non-ASCII) escaped as \n, \t, \', \\ or \xNN, and cut
// after `max_bytes` of input with the full length appended:
//   'no-such-sampler'    'line\nforged'    'aaaaaaaa...' (1048576 bytes)
// So a name can neither forge a log line nor grow a message past a few
// hundred bytes (an error message is a gRPC trailer, and one larger than the
// peer's header limit turns INVALID_ARGUMENT into RESOURCE_EXHAUSTED).
std::string Quoted(std::string_view text, size_t max_bytes = 64);

}  // namespace alignset::server
