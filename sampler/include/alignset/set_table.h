#pragma once

// A table file: the aligned sets a renderer reads at render time, exported
// once from a server's cache (`alignset export`) and loaded here with no
// gRPC, no SQLite and no server. pbrt ships its pmj02bn tables compiled in;
// a render-farm node ships this file.
//
// What it holds: sections, each the canonical keys of one space (the 46
// whole-degree one-direction keys, the 181 quarter-degree ones, or the 4141
// pairs) for one N and one construction. A lattice is stored as its
// generator (4 bytes a key), any other construction as its N points
// (binary64, bit for bit the cached set). A set for any direction is the
// canonical one aligned by the swap and mirror that carry the key onto it,
// as the server aligns it.
//
// The file: an 8-byte magic, a format version, the section directory, the
// payloads, and a CRC-32C of everything before it (little-endian
// throughout). Load refuses, naming the problem, an empty or truncated file,
// a wrong magic or version, a checksum mismatch, an N, construction or space
// out of range, a key count that is not its space's (or, for a section that
// lists its keys, a key out of the space, repeated or out of order), and a
// generator, size or point that cannot be a served set's.

#include <alignset/point_set.h>
#include <alignset/set_choice.h>
#include <alignset/status.h>

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace alignset {

// Which canonical keys a section holds.
enum class TableSpace : uint8_t {
  kOneDirection = 1,   // the 46 whole-degree keys: a direction served to the nearest degree
  kOneQuarter = 2,     // the 181 quarter-degree keys: to the nearest quarter degree
  kTwoDirections = 3,  // the 4141 whole-degree pairs
};
// "1dir", "1dir-quarter", "2dir".
const char* TableSpaceName(TableSpace space);
// 46, 181 or 4141.
uint32_t TableSpaceKeys(TableSpace space);
// The space a name above names; INVALID_ARGUMENT naming the three otherwise.
StatusOr<TableSpace> ParseTableSpace(std::string_view name);

// One section: a space's keys for one N and one construction, in the
// canonical key order (core/align's CanonicalKeyAt: ascending angle).
struct TableSection {
  uint32_t n = 0;
  std::string construction;  // "lattice", "tent-lattice", "optimized" or "net"
  TableSpace space = TableSpace::kOneDirection;
  std::vector<uint32_t> generators;  // a lattice's: one per key held
  std::vector<PointSet> sets;        // any other construction's: one per key held, N points each
  // The canonical keys held (CanonicalKeyIndex, ascending), where the section
  // holds only some: a render fetches or searches only the pairs its pixels
  // choose, of 4141. Empty: every key of the space.
  std::vector<uint32_t> keys;
  // A lattice's points per key held, where a key's lattice has fewer than N
  // (a render's --lattice-size-span chooses N' in [N - span, N] per key; a
  // pixel spends at most N). Empty: N for every key.
  std::vector<uint32_t> sizes;
  // Holds some keys only, or lattices of other sizes than N: such a section
  // needs format version 2 (a table of whole sections stays version 1).
  bool partial() const { return !keys.empty() || !sizes.empty(); }
};

// A served set, aligned to the pixel's directions.
struct TableSet {
  uint32_t n = 0;
  // A lattice (lattice_generator != 0): the points are the rank-1 lattice of
  // this generator under the pixel's shift (ShiftedLatticePoint,
  // <alignset/lattice_points.h>), folded after the shift when `folded`.
  uint32_t lattice_generator = 0;
  bool folded = false;
  // Any other construction: its aligned points, owned by the table (shift
  // them on the torus, ShiftPoint in <alignset/pixel_shift.h>).
  const PointSet* points = nullptr;
};

class SetTable {
 public:
  // One section of a table with its lookup state (opaque).
  struct Section;
  // An (N, construction)'s sections, resolved once (AlignedSampler::Create
  // does): a lookup through them builds no key and allocates nothing. Each
  // null where the table has no such section; `n` and `construction` name
  // them in the lookup's errors (construction must outlive the handle).
  struct Sections {
    uint32_t n = 0;
    std::string_view construction;
    const Section* whole = nullptr;    // TableSpace::kOneDirection
    const Section* quarter = nullptr;  // TableSpace::kOneQuarter
    const Section* pairs = nullptr;    // TableSpace::kTwoDirections
    bool one_direction() const { return whole != nullptr || quarter != nullptr; }
  };

  // The newest file format this library reads and writes. A table whose
  // sections are all whole (no key list, N points a key) is written as
  // version 1, byte for byte what earlier versions wrote; a partial section
  // (TableSection::partial) needs version 2.
  static constexpr uint32_t kFormatVersion = 2;

  // Refused as described above; the message names the file and the problem.
  static StatusOr<std::shared_ptr<const SetTable>> Load(const std::string& path);
  static StatusOr<std::shared_ptr<const SetTable>> Parse(std::span<const uint8_t> bytes);
  // A table made in memory (a renderer that searched its own lattices, a
  // test); the sections are checked as Parse checks a file's.
  static StatusOr<std::shared_ptr<const SetTable>> FromSections(std::vector<TableSection> sections);

  // The file's bytes, and the file written whole (a temporary file renamed
  // into place: a crash never leaves half a table under `path`).
  std::vector<uint8_t> Serialize() const;
  Status Save(const std::string& path) const;
  // The version Serialize writes: 1, or 2 where a section is partial.
  uint32_t format_version() const;

  const std::vector<TableSection>& sections() const;
  // The N with a one-direction section of `construction`, ascending.
  std::vector<uint32_t> PointCounts(std::string_view construction) const;
  bool Has(uint32_t n, std::string_view construction, TableSpace space) const;

  Sections Resolve(uint32_t n, std::string_view construction) const;
  // Aligns every one-direction set of `sections` that a lookup would align on
  // first use (a point set's 180 whole-degree or 720 quarter-degree
  // alignments; lattices need none), so that no pixel's lookup allocates.
  // Pairs of point sets stay aligned on first use (32,400 of them).
  void AlignOneDirectionSets(const Sections& sections) const;

  // The set a pixel's choice reads, aligned. NOT_FOUND naming what is
  // missing when the table has no section or key for it (a two-direction choice
  // from a table without two-direction keys is the caller's fallback to
  // decide: AlignedSampler takes the stronger direction's set), and
  // INVALID_ARGUMENT for a choice out of range.
  StatusOr<TableSet> Find(uint32_t n, std::string_view construction, const SetChoice& choice) const;
  // The same through resolved sections (no key built, no allocation once
  // the sets are aligned).
  StatusOr<TableSet> Find(const Sections& sections, const SetChoice& choice) const;
  // Whether Find would serve the choice (its section is there and holds its
  // key): asked without building an error, e.g. before falling back from a
  // pair the table does not hold.
  bool Holds(const Sections& sections, const SetChoice& choice) const;
  // One direction served on the quarter-degree grid (a kOneQuarter section),
  // or to the nearest whole degree when the table has only whole degrees.
  StatusOr<TableSet> FindOne(uint32_t n, std::string_view construction, double theta_deg) const;

  ~SetTable();
  SetTable(const SetTable&) = delete;
  SetTable& operator=(const SetTable&) = delete;

 private:
  struct Impl;
  explicit SetTable(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace alignset
