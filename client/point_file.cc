#include "client/point_file.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include <unistd.h>

namespace alignset::cli {
namespace {

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string NpyHeader(size_t n) {
  std::string dict = "{'descr': '<f8', 'fortran_order': False, 'shape': (" + std::to_string(n) +
                     ", 2), }";
  // magic(6) + version(2) + header_len(2) + dict + padding + '\n' is a multiple of 64.
  size_t total = 10 + dict.size() + 1;
  dict.append((64 - total % 64) % 64, ' ');
  dict.push_back('\n');
  std::string h("\x93NUMPY\x01\x00", 8);
  const uint16_t len = static_cast<uint16_t>(dict.size());
  h.push_back(static_cast<char>(len & 0xff));
  h.push_back(static_cast<char>(len >> 8));
  return h + dict;
}

std::string Serialize(const std::string& path, const PointSet& points, const std::string& comment) {
  if (EndsWith(path, ".npy")) {
    std::string out = NpyHeader(points.size());
    out.reserve(out.size() + points.size() * 16);
    for (const Point2& p : points) {
      out.append(reinterpret_cast<const char*>(&p.x), 8);
      out.append(reinterpret_cast<const char*>(&p.y), 8);
    }
    return out;
  }
  std::ostringstream os;
  if (!comment.empty()) {
    std::istringstream lines(comment);
    for (std::string line; std::getline(lines, line);) os << "# " << line << "\n";
  }
  char buf[64];
  for (const Point2& p : points) {
    std::snprintf(buf, sizeof(buf), "%.17g %.17g\n", p.x, p.y);
    os << buf;
  }
  return os.str();
}

StatusOr<PointSet> ParseNpy(const std::string& data, const std::string& path) {
  if (data.size() < 10 || data.compare(0, 6, "\x93NUMPY") != 0) {
    return Status::InvalidArgument(path + ": not a .npy file");
  }
  const size_t hlen = static_cast<unsigned char>(data[8]) | (static_cast<unsigned char>(data[9]) << 8);
  if (data.size() < 10 + hlen) return Status::InvalidArgument(path + ": truncated .npy header");
  const std::string header = data.substr(10, hlen);
  if (header.find("'<f8'") == std::string::npos || header.find("False") == std::string::npos) {
    return Status::InvalidArgument(path + ": only C-order little-endian float64 .npy is supported");
  }
  const size_t body = data.size() - 10 - hlen;
  if (body % 16 != 0) return Status::InvalidArgument(path + ": .npy body is not (N, 2) float64");
  PointSet pts(body / 16);
  std::memcpy(pts.data(), data.data() + 10 + hlen, body);
  return pts;
}

}  // namespace

Status WritePointFile(const std::string& path, const PointSet& points, const std::string& comment) {
  if (path.empty()) return Status::InvalidArgument("output path is empty");
  const std::string data = Serialize(path, points, comment);
  const std::string tmp = path + ".tmp." + std::to_string(getpid());
  FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) return Status::InvalidArgument("cannot write " + path + ": " + std::strerror(errno));
  const bool ok = std::fwrite(data.data(), 1, data.size(), f) == data.size() && std::fflush(f) == 0 &&
                  fsync(fileno(f)) == 0;
  const bool closed = std::fclose(f) == 0;
  if (!ok || !closed || std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(tmp.c_str());
    return Status::InvalidArgument("cannot write " + path + ": " + why);
  }
  return Status::Ok();
}

StatusOr<PointSet> ReadPointFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Status::InvalidArgument("cannot read " + path + ": " + std::strerror(errno));
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (EndsWith(path, ".npy")) return ParseNpy(data, path);
  PointSet pts;
  std::istringstream lines(data);
  int line_no = 0;
  for (std::string line; std::getline(lines, line);) {
    ++line_no;
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    Point2 p;
    std::string extra;
    if (!(fields >> p.x >> p.y) || (fields >> extra) || !std::isfinite(p.x) || !std::isfinite(p.y)) {
      return Status::InvalidArgument(path + ":" + std::to_string(line_no) +
                                     ": expected two finite numbers \"x y\"");
    }
    pts.push_back(p);
  }
  if (pts.empty()) return Status::InvalidArgument(path + ": no points");
  return pts;
}

}  // namespace alignset::cli
