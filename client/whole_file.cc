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
  FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) return CannotWrite(path, errno);
  const bool ok = std::fwrite(data.data(), 1, data.size(), f) == data.size() && std::fflush(f) == 0 &&
                  fsync(fileno(f)) == 0;
  int err = errno;
  const bool closed = std::fclose(f) == 0;
  if (ok && !closed) err = errno;
  if (!ok || !closed || std::rename(tmp.c_str(), path.c_str()) != 0) {
    if (ok && closed) err = errno;
    std::remove(tmp.c_str());
    return CannotWrite(path, err);
  }
  return Status::Ok();
}

}  // namespace alignset
