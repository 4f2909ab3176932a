#include "client/whole_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace alignset {
namespace {

Status CannotWrite(const std::string& path, int err) {
  return Status::InvalidArgument("cannot write " + path + ": " + std::strerror(err));
}

}  // namespace

Status WriteWholeFile(const std::string& path, std::string_view data) {
  struct stat st;
  if (stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return CannotWrite(path, errno);
    const bool ok = std::fwrite(data.data(), 1, data.size(), f) == data.size();
    const int err = errno;
    if (std::fclose(f) != 0) return CannotWrite(path, errno);
    return ok ? Status::Ok() : CannotWrite(path, err);
  }
  const std::string tmp = path + ".tmp." + std::to_string(getpid());
  // Each failure reports its own call's errno, read before anything else
  // can overwrite it, and leaves no temporary behind.
  auto fail = [&](int err) {
    std::remove(tmp.c_str());
    return CannotWrite(path, err);
  };
  FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) return CannotWrite(path, errno);
  if (std::fwrite(data.data(), 1, data.size(), f) != data.size() || std::fflush(f) != 0 ||
      fsync(fileno(f)) != 0) {
    const int err = errno;
    std::fclose(f);
    return fail(err);
  }
  if (std::fclose(f) != 0) return fail(errno);
  if (std::rename(tmp.c_str(), path.c_str()) != 0) return fail(errno);
  return Status::Ok();
}

}  // namespace alignset
