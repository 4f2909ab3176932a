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
// Version 2's directory flags: the payload starts with the keys held, then
// the lattices' sizes.
constexpr uint8_t kListsKeys = 1;
constexpr uint8_t kListsSizes = 2;

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

// The keys a section holds: its list's, or its whole space's.
uint64_t HeldKeys(const TableSection& s) { return s.keys.empty() ? TableSpaceKeys(s.space) : s.keys.size(); }

uint8_t Flags(const TableSection& s) {
  return static_cast<uint8_t>((s.keys.empty() ? 0 : kListsKeys) | (s.sizes.empty() ? 0 : kListsSizes));
}

uint64_t PayloadBytes(uint32_t n, uint64_t keys, uint8_t flags, bool lattice) {
  const uint64_t lists = ((flags & kListsKeys) ? 4 : 0) + ((flags & kListsSizes) ? 4 : 0);
  return keys * (lists + (lattice ? 4 : uint64_t{n} * 16));
}

}  // namespace

uint32_t FormatVersion(const std::vector<TableSection>& sections) {
  return std::any_of(sections.begin(), sections.end(), [](const TableSection& s) { return s.partial(); }) ? 2 : 1;
}

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
    const size_t space_keys = TableSpaceKeys(s.space);
    for (size_t i = 0; i < s.keys.size(); ++i) {
      if (s.keys[i] >= space_keys) {
        return Status::InvalidArgument(name + ": key " + std::to_string(s.keys[i]) + " is not in the space's " +
                                       std::to_string(space_keys));
      }
      if (i > 0 && s.keys[i] <= s.keys[i - 1]) {
        return Status::InvalidArgument(name + ": keys not ascending (" + std::to_string(s.keys[i]) + " after " +
                                       std::to_string(s.keys[i - 1]) + ")");
      }
    }
    const size_t keys = HeldKeys(s);
    const size_t have = c->lattice() ? s.generators.size() : s.sets.size();
    if (have != keys || (c->lattice() ? !s.sets.empty() : !s.generators.empty())) {
      return Status::InvalidArgument(name + ": " + std::to_string(have) + " keys where " +
                                     (s.keys.empty() ? "the space has " : "the section lists ") +
                                     std::to_string(keys));
    }
    if (!s.sizes.empty() && (!c->lattice() || s.sizes.size() != keys)) {
      return Status::InvalidArgument(name + ": " + std::to_string(s.sizes.size()) +
                                     " sizes: a lattice section gives one per key held, others none");
    }
    for (size_t k = 0; k < keys; ++k) {
      if (c->lattice()) {
        const uint32_t size = s.sizes.empty() ? s.n : s.sizes[k];
        if (!s.sizes.empty()) {
          if (Status ok = ValidatePointCount(size, *c); !ok.ok() || size > s.n) {
            return Status::InvalidArgument(name + ", key " + std::to_string(k) + ": size " + std::to_string(size) +
                                           (ok.ok() ? " above N" : ": " + ok.message()));
          }
        }
        const uint32_t g = s.generators[k];
        if (g == 0 || g >= size || std::gcd(g, size) != 1) {
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
  Put32(&out, FormatVersion(sections));
  Put32(&out, static_cast<uint32_t>(sections.size()));
  for (const TableSection& s : sections) {
    const bool lattice = FindConstruction(s.construction)->lattice();
    Put32(&out, s.n);
    out.push_back(static_cast<uint8_t>(FindConstruction(s.construction)->kind));
    out.push_back(static_cast<uint8_t>(s.space));
    out.push_back(lattice ? kPayloadGenerators : kPayloadPoints);
    out.push_back(Flags(s));
    Put32(&out, static_cast<uint32_t>(HeldKeys(s)));
    Put64(&out, PayloadBytes(s.n, HeldKeys(s), Flags(s), lattice));
  }
  for (const TableSection& s : sections) {
    for (uint32_t k : s.keys) Put32(&out, k);
    for (uint32_t size : s.sizes) Put32(&out, size);
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
  if (version < 1 || version > SetTable::kFormatVersion) {
    return Status::InvalidArgument("format version " + std::to_string(version) + "; this library reads versions 1 to " +
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
    const uint8_t flags = e[7];
    const uint8_t known = version >= 2 ? (kListsKeys | kListsSizes) : 0;
    if ((flags & ~known) != 0 || ((flags & kListsSizes) && !c->lattice())) {
      return Status::InvalidArgument(name + ": flags " + std::to_string(flags) + " this format version " +
                                     std::to_string(version) + " does not have for this construction");
    }
    const uint32_t keys = Get32(e + 8);
    if ((flags & kListsKeys) ? (keys == 0 || keys > TableSpaceKeys(s.space)) : keys != TableSpaceKeys(s.space)) {
      return Status::InvalidArgument(name + ": " + std::to_string(keys) + " keys where the space has " +
                                     std::to_string(TableSpaceKeys(s.space)));
    }
    if (e[6] != (c->lattice() ? kPayloadGenerators : kPayloadPoints)) {
      return Status::InvalidArgument(name + ": a payload of the wrong kind for its construction");
    }
    const uint64_t payload = Get64(e + 12);
    const uint64_t expected_payload = PayloadBytes(s.n, keys, flags, c->lattice());
    if (payload != expected_payload) {
      return Status::InvalidArgument(name + ": " + std::to_string(payload) + " payload bytes, expected " +
                                     std::to_string(expected_payload));
    }
    const uint8_t* p = bytes.data() + at;
    for (uint32_t list : {kListsKeys, kListsSizes}) {
      if (!(flags & list)) continue;
      std::vector<uint32_t>& into = list == kListsKeys ? s.keys : s.sizes;
      into.resize(keys);
      for (uint32_t k = 0; k < keys; ++k) into[k] = Get32(p + 4 * k);
      p += uint64_t{keys} * 4;
    }
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
  // One encoding a table: whole sections are written as version 1.
  if (version != FormatVersion(sections)) {
    return Status::InvalidArgument("format version " + std::to_string(version) + " for a table whose sections " +
                                   (version == 1 ? "are partial" : "are all whole (written as version 1)"));
  }
  return sections;
}

}  // namespace alignset::sampler
