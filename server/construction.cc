#include "server/construction.h"

#include "server/log_text.h"

namespace alignset::server {

StatusOr<const Construction*> ParseConstruction(const std::string& name) {
  if (const Construction* c = FindConstruction(name)) return c;
  // Quoted: the name comes from the client (escaped, cut after 64 bytes).
  return Status::InvalidArgument("unknown construction " + Quoted(name) + ": the known ones are " +
                                 KnownConstructionNames());
}

}  // namespace alignset::server
