#include "render/npy.h"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

namespace alignset::render {

Status WriteNpy(const std::string& path, const std::vector<size_t>& shape,
                const std::vector<double>& data) {
  size_t count = 1;
  std::string dims;
  for (size_t i = 0; i < shape.size(); ++i) {
    count *= shape[i];
    dims += (i ? ", " : "") + std::to_string(shape[i]);
  }
  if (shape.size() == 1) dims += ",";  // a one-element Python tuple
  if (count != data.size()) {
    return Status::InvalidArgument("npy: shape holds " + std::to_string(count) +
                                   " values, data has " + std::to_string(data.size()));
  }
  std::string dict = "{'descr': '<f8', 'fortran_order': False, 'shape': (" + dims + "), }";
  const size_t total = 10 + dict.size() + 1;
  dict.append((64 - total % 64) % 64, ' ');
  dict.push_back('\n');
  std::string out("\x93NUMPY\x01\x00", 8);
  out.push_back(static_cast<char>(dict.size() & 0xff));
  out.push_back(static_cast<char>(dict.size() >> 8));
  out += dict;
  out.append(reinterpret_cast<const char*>(data.data()), data.size() * sizeof(double));
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) return Status::InvalidArgument("cannot write " + path);
    f.write(out.data(), static_cast<std::streamsize>(out.size()));
    if (!f) return Status::InvalidArgument("cannot write " + path);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    return Status::InvalidArgument("cannot write " + path + ": " + std::strerror(errno));
  }
  return Status::Ok();
}

StatusOr<std::vector<double>> ReadNpy(const std::string& path, std::vector<size_t>* shape) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return Status::InvalidArgument("cannot read " + path);
  std::string data((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (data.size() < 10 || data.compare(0, 6, "\x93NUMPY") != 0) {
    return Status::InvalidArgument(path + ": not a .npy file");
  }
  const size_t hlen = static_cast<uint8_t>(data[8]) | (static_cast<uint8_t>(data[9]) << 8);
  if (data.size() < 10 + hlen) return Status::InvalidArgument(path + ": truncated .npy header");
  const std::string header = data.substr(10, hlen);
  if (header.find("'<f8'") == std::string::npos || header.find("False") == std::string::npos) {
    return Status::InvalidArgument(path + ": only C-order little-endian float64 is read");
  }
  const size_t open = header.find('(', header.find("'shape'")), close = header.find(')', open);
  if (open == std::string::npos || close == std::string::npos) {
    return Status::InvalidArgument(path + ": no shape in the .npy header");
  }
  shape->clear();
  std::stringstream dims(header.substr(open + 1, close - open - 1));
  size_t count = 1;
  for (std::string item; std::getline(dims, item, ',');) {
    if (item.find_first_not_of(' ') == std::string::npos) continue;
    shape->push_back(std::stoul(item));
    count *= shape->back();
  }
  const size_t body = data.size() - 10 - hlen;
  if (body != count * sizeof(double)) return Status::InvalidArgument(path + ": body does not match its shape");
  std::vector<double> values(count);
  std::memcpy(values.data(), data.data() + 10 + hlen, body);
  return values;
}

}  // namespace alignset::render
