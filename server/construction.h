#pragma once

#include <string>

#include "core/optimize/construction.h"
#include "core/util/status.h"

namespace alignset::server {

// A request's construction name (AlignedSetRequest.construction) at the
// boundary: "" or a name of Constructions() -> that construction; anything
// else INVALID_ARGUMENT quoting the name (escaped, cut) and listing the known
// ones.
StatusOr<const Construction*> ParseConstruction(const std::string& name);

}  // namespace alignset::server
