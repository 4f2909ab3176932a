#include <alignset/npy.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "client/whole_file.h"

namespace alignset {
namespace {

// The header dictionary of a .npy file: dtype, order, shape.
struct NpyHeaderInfo {
  std::string descr;
  bool fortran_order = false;
  std::vector<size_t> shape;
};

StatusOr<NpyHeaderInfo> ParseNpyHeader(const std::string& h, const std::string& path) {
  NpyHeaderInfo info;
  auto value_of = [&](const std::string& key) -> std::string {
    const size_t k = h.find("'" + key + "'");
    if (k == std::string::npos) return "";
    const size_t colon = h.find(':', k);
    return colon == std::string::npos ? "" : h.substr(colon + 1);
  };
  const std::string descr = value_of("descr");
  const size_t q1 = descr.find('\'');
  const size_t q2 = q1 == std::string::npos ? q1 : descr.find('\'', q1 + 1);
  if (q2 == std::string::npos) return Status::InvalidArgument(path + ": .npy header without a dtype");
  info.descr = descr.substr(q1 + 1, q2 - q1 - 1);
  const std::string order = value_of("fortran_order");
  info.fortran_order = order.find("True") < order.find("False");
  const std::string shape = value_of("shape");
  const size_t open = shape.find('('), close = shape.find(')');
  if (open == std::string::npos || close == std::string::npos || close < open) {
    return Status::InvalidArgument(path + ": .npy header without a shape");
  }
  std::stringstream dims(shape.substr(open + 1, close - open - 1));
  for (std::string d; std::getline(dims, d, ',');) {
    if (d.find_first_not_of(" ") == std::string::npos) continue;
    char* end = nullptr;
    const unsigned long long v = std::strtoull(d.c_str(), &end, 10);
    if (end == d.c_str()) return Status::InvalidArgument(path + ": bad .npy shape '" + shape + "'");
    info.shape.push_back(static_cast<size_t>(v));
  }
  return info;
}

}  // namespace

std::string NpyShapeText(const std::vector<size_t>& dims) {
  std::string s = "(";
  for (size_t i = 0; i < dims.size(); ++i) s += (i ? ", " : "") + std::to_string(dims[i]);
  return s + (dims.size() == 1 ? ",)" : ")");
}

std::string NpyHeader(const std::vector<size_t>& shape, bool fortran_order, const std::string& descr) {
  std::string dict = "{'descr': '" + descr + "', 'fortran_order': " +
                     (fortran_order ? "True" : "False") + ", 'shape': " + NpyShapeText(shape) + ", }";
  // magic(6) + version(2) + header_len(2) + dict + padding + '\n' is a multiple of 64.
  const size_t total = 10 + dict.size() + 1;
  dict.append((64 - total % 64) % 64, ' ');
  dict.push_back('\n');
  std::string h("\x93NUMPY\x01\x00", 8);
  const uint16_t len = static_cast<uint16_t>(dict.size());
  h.push_back(static_cast<char>(len & 0xff));
  h.push_back(static_cast<char>(len >> 8));
  return h + dict;
}

StatusOr<NpyArray> ParseNpyArray(const std::string& data, const std::string& path,
                                 const NpyShapeCheck& check_shape) {
  if (data.size() < 10 || data.compare(0, 6, "\x93NUMPY") != 0) {
    return Status::InvalidArgument(path + ": not a .npy file");
  }
  const auto byte = [&](size_t i) { return static_cast<size_t>(static_cast<unsigned char>(data[i])); };
  // Version 1 has a 2-byte header length, versions 2 and 3 a 4-byte one.
  const size_t len_bytes = byte(6) == 1 ? 2 : 4;
  if (data.size() < 8 + len_bytes) return Status::InvalidArgument(path + ": truncated .npy header");
  size_t hlen = 0;
  for (size_t i = 0; i < len_bytes; ++i) hlen |= byte(8 + i) << (8 * i);
  const size_t body_at = 8 + len_bytes + hlen;
  if (data.size() < body_at) return Status::InvalidArgument(path + ": truncated .npy header");
  auto info = ParseNpyHeader(data.substr(8 + len_bytes, hlen), path);
  if (!info.ok()) return info.status();
  size_t item = 0;
  if (info->descr == "<f8") {
    item = 8;
  } else if (info->descr == "<f4") {
    item = 4;
  } else {
    return Status::InvalidArgument(path + ": dtype '" + info->descr +
                                   "' is not supported; save little-endian float64 ('<f8')");
  }
  const std::vector<size_t>& dims = info->shape;
  if (check_shape) {
    if (Status s = check_shape(dims); !s.ok()) return s;
  }
  // The element count; a shape whose product overflows cannot match the body.
  size_t count = 1;
  for (size_t d : dims) {
    if (d != 0 && count > SIZE_MAX / 8 / d) {
      return Status::InvalidArgument(path + ": shape " + NpyShapeText(dims) + " is too large");
    }
    count *= d;
  }
  if (data.size() - body_at != count * item) {
    return Status::InvalidArgument(path + ": .npy body holds " + std::to_string(data.size() - body_at) +
                                   " bytes, its shape " + NpyShapeText(dims) + " needs " +
                                   std::to_string(count * item));
  }
  const char* body = data.data() + body_at;
  auto load = [&](size_t flat) {
    if (item == 8) {
      double v;
      std::memcpy(&v, body + flat * 8, 8);
      return v;
    }
    float v;
    std::memcpy(&v, body + flat * 4, 4);
    return static_cast<double>(v);
  };
  NpyArray out;
  out.shape = dims;
  out.values.resize(count);
  if (!info->fortran_order || dims.size() <= 1) {
    for (size_t i = 0; i < count; ++i) out.values[i] = load(i);
    return out;
  }
  // Fortran order: walk the C-order multi-index and place each element.
  std::vector<size_t> fortran_stride(dims.size(), 1);
  for (size_t k = 1; k < dims.size(); ++k) fortran_stride[k] = fortran_stride[k - 1] * dims[k - 1];
  std::vector<size_t> idx(dims.size(), 0);
  for (size_t c = 0; c < count; ++c) {
    size_t f = 0;
    for (size_t k = 0; k < dims.size(); ++k) f += idx[k] * fortran_stride[k];
    out.values[c] = load(f);
    for (size_t k = dims.size(); k-- > 0;) {
      if (++idx[k] < dims[k]) break;
      idx[k] = 0;
    }
  }
  return out;
}

StatusOr<NpyArray> ReadNpy(const std::string& path, const NpyShapeCheck& check_shape) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return Status::InvalidArgument("cannot read " + path);
  const std::string data((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  return ParseNpyArray(data, path, check_shape);
}

Status WriteNpy(const std::string& path, const std::vector<size_t>& shape,
                const std::vector<double>& data) {
  size_t count = 1;
  for (size_t d : shape) count *= d;
  if (count != data.size()) {
    return Status::InvalidArgument("npy: shape holds " + std::to_string(count) +
                                   " values, data has " + std::to_string(data.size()));
  }
  std::string out = NpyHeader(shape);
  out.append(reinterpret_cast<const char*>(data.data()), data.size() * sizeof(double));
  return WriteWholeFile(path, out);
}

}  // namespace alignset
