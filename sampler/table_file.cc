#include "sampler/table_file.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>
#include <set>
#include <string>
#include <tuple>

#include "core/optimize/construction.h"
#include "core/optimize/optimizer.h"
#include "core/optimize/point_count.h"
#include "core/util/crc32c.h"

namespace alignset::sampler {
namespace {

constexpr size_t kHeaderBytes = 16;
constexpr size_t kEntryBytes = 20;
constexpr size_t kTrailerBytes = 4;
constexpr uint8_t kPayloadGenerators = 1;
constexpr uint8_t kPayloadPoints = 2;

void Put32(std::vector<uint8_t>* out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out->push_back(static_cast<uint8_t>(v >> (8 * i)));
}
void Put64(std::vector<uint8_t>* out, uint64_t v) {
  for (int i = 0; i < 8; ++i) out->push_back(static_cast<uint8_t>(v >> (8 * i)));
}
uint32_t Get32(const uint8_t* p) {
  uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= static_cast<uint32_t>(p[i]) << (8 * i);
  return v;
}
uint64_t Get64(const uint8_t* p) {
  uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= static_cast<uint64_t>(p[i]) << (8 * i);
  return v;
}

const Construction* ConstructionByCode(uint8_t code) {
  for (const Construction& c : Constructions()) {
    if (static_cast<uint8_t>(c.kind) == code) return &c;
  }
  return nullptr;
}

bool KnownSpace(uint8_t space) { return space >= 1 && space <= 3; }

std::string SectionName(uint32_t n, std::string_view construction, TableSpace space) {
  return "section N=" + std::to_string(n) + " " + std::string(construction) + " " + TableSpaceName(space);
}

uint64_t PayloadBytes(const TableSection& s, bool lattice) {
  const uint64_t keys = TableSpaceKeys(s.space);
  return lattice ? keys * 4 : keys * uint64_t{s.n} * 16;
}

}  // namespace

Status CheckSections(const std::vector<TableSection>& sections) {
  if (sections.empty()) return Status::InvalidArgument("the table has no sections");
  std::set<std::tuple<uint32_t, std::string, int>> seen;
  for (const TableSection& s : sections) {
    const Construction* c = FindConstruction(s.construction);
    if (c == nullptr || s.construction.empty()) {
      return Status::InvalidArgument("unknown construction '" + s.construction + "'");
    }
    if (!KnownSpace(static_cast<uint8_t>(s.space))) {
      return Status::InvalidArgument("unknown space " + std::to_string(static_cast<int>(s.space)));
    }
    const std::string name = SectionName(s.n, s.construction, s.space);
    if (Status size = ValidatePointCount(s.n, *c); !size.ok()) return Status::InvalidArgument(name + ": " + size.message());
    if (!seen.insert({s.n, s.construction, static_cast<int>(s.space)}).second) {
      return Status::InvalidArgument(name + " appears twice");
    }
    const size_t keys = TableSpaceKeys(s.space);
    const size_t have = c->lattice() ? s.generators.size() : s.sets.size();
    if (have != keys || (c->lattice() ? !s.sets.empty() : !s.generators.empty())) {
      return Status::InvalidArgument(name + ": " + std::to_string(have) + " keys where the space has " +
                                     std::to_string(keys));
    }
    for (size_t k = 0; k < keys; ++k) {
      if (c->lattice()) {
        const uint32_t g = s.generators[k];
        if (g == 0 || g >= s.n || std::gcd(g, s.n) != 1) {
          return Status::InvalidArgument(name + ", key " + std::to_string(k) + ": generator " + std::to_string(g) +
                                         " out of range (1 <= g < N, coprime to N)");
        }
        continue;
      }
      const PointSet& p = s.sets[k];
      if (p.size() != s.n) {
        return Status::InvalidArgument(name + ", key " + std::to_string(k) + ": " + std::to_string(p.size()) +
                                       " points, not N");
      }
      for (size_t i = 0; i < p.size(); ++i) {
        for (double v : {p[i].x, p[i].y}) {
          if (!(std::isfinite(v) && v >= 0.0 && v < 1.0)) {
            return Status::InvalidArgument(name + ", key " + std::to_string(k) + ": point " + std::to_string(i) +
                                           " is not in [0, 1)");
          }
        }
      }
    }
  }
  return Status::Ok();
}

std::vector<uint8_t> EncodeTable(const std::vector<TableSection>& sections) {
  std::vector<uint8_t> out(kTableMagic, kTableMagic + sizeof(kTableMagic));
  Put32(&out, SetTable::kFormatVersion);
  Put32(&out, static_cast<uint32_t>(sections.size()));
  for (const TableSection& s : sections) {
    const bool lattice = FindConstruction(s.construction)->lattice();
    Put32(&out, s.n);
    out.push_back(static_cast<uint8_t>(FindConstruction(s.construction)->kind));
    out.push_back(static_cast<uint8_t>(s.space));
    out.push_back(lattice ? kPayloadGenerators : kPayloadPoints);
    out.push_back(0);
    Put32(&out, TableSpaceKeys(s.space));
    Put64(&out, PayloadBytes(s, lattice));
  }
  for (const TableSection& s : sections) {
    for (uint32_t g : s.generators) Put32(&out, g);
    for (const PointSet& set : s.sets) {
      for (const Point2& p : set) {
        Put64(&out, std::bit_cast<uint64_t>(p.x));
        Put64(&out, std::bit_cast<uint64_t>(p.y));
      }
    }
  }
  Put32(&out, Crc32c(out));
  return out;
}

StatusOr<std::vector<TableSection>> DecodeTable(std::span<const uint8_t> bytes) {
  if (bytes.empty()) return Status::DataLoss("empty file: not a table");
  const size_t size = bytes.size();
  const size_t head = std::min(size, sizeof(kTableMagic));
  if (std::memcmp(bytes.data(), kTableMagic, head) != 0) {
    return Status::InvalidArgument("not an alignset table (wrong magic)");
  }
  if (size < kHeaderBytes + kTrailerBytes) {
    return Status::DataLoss("truncated: " + std::to_string(size) + " bytes, less than a header");
  }
  const uint32_t version = Get32(bytes.data() + 8);
  if (version != SetTable::kFormatVersion) {
    return Status::InvalidArgument("format version " + std::to_string(version) + "; this library reads version " +
                                   std::to_string(SetTable::kFormatVersion));
  }
  const uint64_t count = Get32(bytes.data() + 12);
  const uint64_t directory_end = kHeaderBytes + count * kEntryBytes;
  if (directory_end + kTrailerBytes > size) {
    return Status::DataLoss("truncated: " + std::to_string(size) + " bytes, the directory of " +
                            std::to_string(count) + " sections alone needs " + std::to_string(directory_end + 4));
  }
  uint64_t expected = directory_end + kTrailerBytes;
  for (uint64_t i = 0; i < count; ++i) {
    const uint64_t payload = Get64(bytes.data() + kHeaderBytes + i * kEntryBytes + 12);
    if (payload > size) return Status::DataLoss("truncated: section " + std::to_string(i) + " runs past the end");
    expected += payload;
  }
  if (expected > size) {
    return Status::DataLoss("truncated: " + std::to_string(size) + " bytes of " + std::to_string(expected));
  }
  if (expected < size) {
    return Status::DataLoss(std::to_string(size - expected) + " bytes after the table's end");
  }
  const uint32_t stored = Get32(bytes.data() + size - kTrailerBytes);
  const uint32_t actual = Crc32c(bytes.first(size - kTrailerBytes));
  if (stored != actual) {
    char msg[96];
    std::snprintf(msg, sizeof(msg), "checksum mismatch: stored crc32c %08x, the file has %08x", stored, actual);
    return Status::DataLoss(msg);
  }
  std::vector<TableSection> sections;
  size_t at = directory_end;
  for (uint64_t i = 0; i < count; ++i) {
    const uint8_t* e = bytes.data() + kHeaderBytes + i * kEntryBytes;
    TableSection s;
    s.n = Get32(e);
    const Construction* c = ConstructionByCode(e[4]);
    if (c == nullptr) return Status::InvalidArgument("section " + std::to_string(i) + ": unknown construction code " + std::to_string(e[4]));
    if (!KnownSpace(e[5])) return Status::InvalidArgument("section " + std::to_string(i) + ": unknown space " + std::to_string(e[5]));
    s.construction = std::string(c->name);
    s.space = static_cast<TableSpace>(e[5]);
    const std::string name = SectionName(s.n, s.construction, s.space);
    if (Status size = ValidatePointCount(s.n, *c); !size.ok()) return Status::InvalidArgument(name + ": " + size.message());
    const uint32_t keys = Get32(e + 8);
    if (keys != TableSpaceKeys(s.space)) {
      return Status::InvalidArgument(name + ": " + std::to_string(keys) + " keys where the space has " +
                                     std::to_string(TableSpaceKeys(s.space)));
    }
    if (e[6] != (c->lattice() ? kPayloadGenerators : kPayloadPoints)) {
      return Status::InvalidArgument(name + ": a payload of the wrong kind for its construction");
    }
    const uint64_t payload = Get64(e + 12);
    if (payload != PayloadBytes(s, c->lattice())) {
      return Status::InvalidArgument(name + ": " + std::to_string(payload) + " payload bytes, expected " +
                                     std::to_string(PayloadBytes(s, c->lattice())));
    }
    const uint8_t* p = bytes.data() + at;
    if (c->lattice()) {
      s.generators.resize(keys);
      for (uint32_t k = 0; k < keys; ++k) s.generators[k] = Get32(p + 4 * k);
    } else {
      s.sets.assign(keys, PointSet(s.n));
      for (uint32_t k = 0; k < keys; ++k) {
        for (uint32_t j = 0; j < s.n; ++j) {
          const uint8_t* q = p + (uint64_t{k} * s.n + j) * 16;
          s.sets[k][j] = {std::bit_cast<double>(Get64(q)), std::bit_cast<double>(Get64(q + 8))};
        }
      }
    }
    at += payload;
    sections.push_back(std::move(s));
  }
  return sections;
}

}  // namespace alignset::sampler
