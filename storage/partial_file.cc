#include "storage/partial_file.h"

#include <filesystem>

namespace alignset::storage {
namespace {

constexpr const char* kSuffixes[] = {"", "-wal", "-shm"};

}  // namespace

Status ClearPartialFile(const std::string& partial, bool overwrite) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const char* suffix : kSuffixes) {
    if (!fs::exists(partial + suffix, ec)) continue;
    if (!overwrite) {
      return Status::InvalidArgument(partial + suffix + " exists (an interrupted or running merge or "
                                     "recover); remove it, or pass --force to overwrite it");
    }
    fs::remove(partial + suffix, ec);
  }
  return Status::Ok();
}

void RemovePartialFile(const std::string& partial) {
  std::error_code ec;
  for (const char* suffix : kSuffixes) std::filesystem::remove(partial + suffix, ec);
}

}  // namespace alignset::storage
