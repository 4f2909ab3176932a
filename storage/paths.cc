#include "storage/paths.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace alignset::storage {
namespace {

const char* NonEmptyEnv(const char* name) {
  const char* v = std::getenv(name);
  return (v != nullptr && *v != '\0') ? v : nullptr;
}

}  // namespace

StatusOr<std::string> DefaultDatabasePath() {
  namespace fs = std::filesystem;
  fs::path dir;
  if (const char* d = NonEmptyEnv("ALIGNSET_DATA_DIR")) {
    dir = d;
  } else if (const char* x = NonEmptyEnv("XDG_DATA_HOME"); x != nullptr && fs::path(x).is_absolute()) {
    dir = fs::path(x) / "alignset";
  } else if (const char* h = NonEmptyEnv("HOME")) {
    dir = fs::path(h) / ".local" / "share" / "alignset";
  } else {
    return Status::InvalidArgument(
        "no data directory: set ALIGNSET_DATA_DIR (or XDG_DATA_HOME or HOME)");
  }
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    return Status::Unavailable("cannot create data directory " + dir.string() + ": " + ec.message());
  }
  if (!fs::is_directory(dir, ec)) {
    return Status::Unavailable(dir.string() + " is not a directory");
  }
  return (dir / "alignset.sqlite").string();
}

}  // namespace alignset::storage
