#include <alignset/set_table.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <tuple>

#include "core/align/canonical.h"
#include "core/optimize/aligned_lattice.h"
#include "core/optimize/construction.h"
#include "sampler/table_file.h"

namespace alignset {

const char* TableSpaceName(TableSpace space) {
  switch (space) {
    case TableSpace::kOneDirection: return "1dir";
    case TableSpace::kOneQuarter: return "1dir-quarter";
    case TableSpace::kTwoDirections: return "2dir";
  }
  return "?";
}

uint32_t TableSpaceKeys(TableSpace space) {
  switch (space) {
    case TableSpace::kOneDirection: return static_cast<uint32_t>(CanonicalKeyCount(1));
    case TableSpace::kOneQuarter: return static_cast<uint32_t>(CanonicalKeyCount(1, AngleGrid::kQuarterDegree));
    case TableSpace::kTwoDirections: return static_cast<uint32_t>(CanonicalKeyCount(2));
  }
  return 0;
}

StatusOr<TableSpace> ParseTableSpace(std::string_view name) {
  for (TableSpace t : {TableSpace::kOneDirection, TableSpace::kOneQuarter, TableSpace::kTwoDirections}) {
    if (name == TableSpaceName(t)) return t;
  }
  return Status::InvalidArgument("--space: '" + std::string(name) + "' is not 1dir, 1dir-quarter or 2dir");
}

namespace {

// Where a served direction (or pair) lives in its space, and the element
// that aligns the canonical set onto it: the server's mapping
// (core/align/canonical.h), computed once for every served value.
struct Served {
  uint32_t index = 0;
  AlignOps ops;
};

// Served whole degrees 0..179 and quarter degrees 0..719 (index = 4 * deg).
const std::vector<Served>& ServedOne(AngleGrid grid) {
  static const std::array<std::vector<Served>, 2> tables = [] {
    std::array<std::vector<Served>, 2> t;
    for (int g = 0; g < 2; ++g) {
      const AngleGrid grid = g == 0 ? AngleGrid::kWholeDegree : AngleGrid::kQuarterDegree;
      const int steps = StepsPerDegree(grid);
      for (int k = 0; k < 180 * steps; ++k) {
        const auto c = Canonicalize({static_cast<double>(k) / steps}, grid);
        t[g].push_back({static_cast<uint32_t>(*CanonicalKeyIndex(c->key, grid)), c->ops});
      }
    }
    return t;
  }();
  return tables[grid == AngleGrid::kWholeDegree ? 0 : 1];
}

// Served pairs (a, b), a < b whole degrees, at a * 180 + b.
const std::vector<Served>& ServedTwo() {
  static const std::vector<Served> table = [] {
    std::vector<Served> t(180 * 180);
    for (int a = 0; a < 180; ++a) {
      for (int b = a + 1; b < 180; ++b) {
        const auto c = Canonicalize({static_cast<double>(a), static_cast<double>(b)});
        t[static_cast<size_t>(a) * 180 + b] = {static_cast<uint32_t>(*CanonicalKeyIndex(c->key)), c->ops};
      }
    }
    return t;
  }();
  return table;
}

// A section's aligned sets, built on first use (each is N points; a table of
// optimized two-direction sets would not fit in memory aligned up front).
class AlignedSets {
 public:
  explicit AlignedSets(size_t count) : sets_(count), once_(new std::once_flag[count]) {}
  const PointSet& Get(size_t slot, const PointSet& canonical, AlignOps ops) const {
    std::call_once(once_[slot], [&] { sets_[slot] = std::make_unique<PointSet>(Align(canonical, ops)); });
    return *sets_[slot];
  }

 private:
  mutable std::vector<std::unique_ptr<PointSet>> sets_;
  std::unique_ptr<std::once_flag[]> once_;
};

}  // namespace

struct SetTable::Section {
  const TableSection* section = nullptr;
  const Construction* construction = nullptr;
  std::unique_ptr<AlignedSets> aligned;  // a point set's alignments, built on first use
  // A section that lists its keys: each canonical key's place in its
  // payload, kAbsent for a key it does not hold (4141 entries at most).
  static constexpr uint32_t kAbsent = ~0u;
  std::vector<uint32_t> place;

  uint32_t Place(uint32_t key) const { return place.empty() ? key : place[key]; }
  bool Holds(const Served& s) const { return Place(s.index) != kAbsent; }
  // The aligned set of a served slot whose key the section holds.
  TableSet Aligned(size_t slot, const Served& s) const {
    const uint32_t k = Place(s.index);
    TableSet out;
    out.n = section->sizes.empty() ? section->n : section->sizes[k];
    if (construction->lattice()) {
      out.lattice_generator = MapLatticeGenerator(out.n, section->generators[k], s.ops.swap, s.ops.invert,
                                                  s.ops.invert_y);
      out.folded = construction->folded();
    } else {
      out.points = &aligned->Get(slot, section->sets[k], s.ops);
    }
    return out;
  }
};

// (N, construction, space), compared as a view so that a lookup by a
// string_view builds no string (libstdc++'s tuple comparison does not mix a
// string with a string_view under every compiler).
struct SectionKeyLess {
  using is_transparent = void;
  using Key = std::tuple<uint32_t, std::string, int>;
  using View = std::tuple<uint32_t, std::string_view, int>;
  static View AsView(const Key& k) { return {std::get<0>(k), std::get<1>(k), std::get<2>(k)}; }
  static const View& AsView(const View& v) { return v; }
  template <class A, class B>
  bool operator()(const A& a, const B& b) const { return AsView(a) < AsView(b); }
};

struct SetTable::Impl {
  std::vector<TableSection> sections;
  // (N, construction, space) -> the section and, for points, its aligned sets.
  std::map<SectionKeyLess::Key, Section, SectionKeyLess> by_key;

  const Section* Find(uint32_t n, std::string_view construction, TableSpace space) const {
    auto it = by_key.find(SectionKeyLess::View(n, construction, static_cast<int>(space)));
    return it == by_key.end() ? nullptr : &it->second;
  }
};

SetTable::SetTable(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
SetTable::~SetTable() = default;

StatusOr<std::shared_ptr<const SetTable>> SetTable::FromSections(std::vector<TableSection> sections) {
  if (Status s = sampler::CheckSections(sections); !s.ok()) return s;
  auto impl = std::make_unique<Impl>();
  impl->sections = std::move(sections);
  for (const TableSection& s : impl->sections) {
    Section e;
    e.section = &s;
    e.construction = FindConstruction(s.construction);
    if (!e.construction->lattice()) {
      const size_t slots = s.space == TableSpace::kTwoDirections ? 180 * 180
                           : s.space == TableSpace::kOneQuarter  ? 720
                                                                 : 180;
      e.aligned = std::make_unique<AlignedSets>(slots);
    }
    if (!s.keys.empty()) {
      e.place.assign(TableSpaceKeys(s.space), Section::kAbsent);
      for (size_t k = 0; k < s.keys.size(); ++k) e.place[s.keys[k]] = static_cast<uint32_t>(k);
    }
    impl->by_key.emplace(std::make_tuple(s.n, s.construction, static_cast<int>(s.space)), std::move(e));
  }
  return std::shared_ptr<const SetTable>(new SetTable(std::move(impl)));
}

StatusOr<std::shared_ptr<const SetTable>> SetTable::Parse(std::span<const uint8_t> bytes) {
  auto sections = sampler::DecodeTable(bytes);
  if (!sections.ok()) return sections.status();
  return FromSections(std::move(sections).value());
}

StatusOr<std::shared_ptr<const SetTable>> SetTable::Load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Status::NotFound("table file " + path + ": cannot be opened");
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) return Status::DataLoss("table file " + path + ": read failed");
  auto table = Parse(bytes);
  if (!table.ok()) {
    const Status& s = table.status();
    const std::string m = "table file " + path + ": " + s.message();
    return s.code() == Status::Code::kDataLoss ? Status::DataLoss(m) : Status::InvalidArgument(m);
  }
  return table;
}

std::vector<uint8_t> SetTable::Serialize() const { return sampler::EncodeTable(impl_->sections); }

uint32_t SetTable::format_version() const { return sampler::FormatVersion(impl_->sections); }

Status SetTable::Save(const std::string& path) const {
  const std::vector<uint8_t> bytes = Serialize();
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) return Status::InvalidArgument("table file " + path + ": cannot write " + tmp);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    out.flush();
    if (!out) {
      std::remove(tmp.c_str());
      return Status::Internal("table file " + path + ": write failed (disk full?)");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    return Status::Internal("table file " + path + ": cannot rename " + tmp + " into place");
  }
  return Status::Ok();
}

const std::vector<TableSection>& SetTable::sections() const { return impl_->sections; }

std::vector<uint32_t> SetTable::PointCounts(std::string_view construction) const {
  std::vector<uint32_t> out;
  for (const TableSection& s : impl_->sections) {
    if (s.construction == construction && s.space != TableSpace::kTwoDirections &&
        (out.empty() || out.back() != s.n)) {
      out.push_back(s.n);
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

bool SetTable::Has(uint32_t n, std::string_view construction, TableSpace space) const {
  return impl_->Find(n, construction, space) != nullptr;
}

SetTable::Sections SetTable::Resolve(uint32_t n, std::string_view construction) const {
  Sections s;
  s.n = n;
  s.construction = construction;
  s.whole = impl_->Find(n, construction, TableSpace::kOneDirection);
  s.quarter = impl_->Find(n, construction, TableSpace::kOneQuarter);
  s.pairs = impl_->Find(n, construction, TableSpace::kTwoDirections);
  return s;
}

void SetTable::AlignOneDirectionSets(const Sections& sections) const {
  for (const auto& [section, grid] : {std::pair{sections.whole, AngleGrid::kWholeDegree},
                                      std::pair{sections.quarter, AngleGrid::kQuarterDegree}}) {
    if (section == nullptr || !section->aligned) continue;
    const std::vector<Served>& served = ServedOne(grid);
    for (size_t slot = 0; slot < served.size(); ++slot) {
      if (section->Holds(served[slot])) section->Aligned(slot, served[slot]);
    }
  }
}

StatusOr<TableSet> SetTable::Find(uint32_t n, std::string_view construction, const SetChoice& choice) const {
  return Find(Resolve(n, construction), choice);
}

namespace {

// Where a choice is served from: its section (null: the table has none), its
// slot among that section's served values, and the key and alignment it
// is served by.
struct Lookup {
  const SetTable::Section* section = nullptr;
  TableSpace space = TableSpace::kOneDirection;
  size_t slot = 0;
  const Served* served = nullptr;
};

// INVALID_ARGUMENT for a choice out of range; no allocation otherwise.
StatusOr<Lookup> Locate(const SetTable::Sections& sections, const SetChoice& choice) {
  switch (choice.kind) {
    case SetChoice::Kind::kFallback:
      return Status::InvalidArgument("a fallback choice reads no set");
    case SetChoice::Kind::kOne: {
      if (choice.a < 0 || choice.a >= 180) return Status::InvalidArgument("served degree out of [0, 180)");
      const size_t deg = static_cast<size_t>(choice.a);
      if (sections.whole != nullptr) {
        return Lookup{sections.whole, TableSpace::kOneDirection, deg, &ServedOne(AngleGrid::kWholeDegree)[deg]};
      }
      // A quarter-degree section holds every whole degree too.
      if (sections.quarter != nullptr) {
        return Lookup{sections.quarter, TableSpace::kOneQuarter, deg * 4, &ServedOne(AngleGrid::kQuarterDegree)[deg * 4]};
      }
      return Lookup{nullptr, TableSpace::kOneDirection, deg, nullptr};
    }
    case SetChoice::Kind::kTwo: {
      if (choice.a < 0 || choice.b >= 180 || choice.a >= choice.b) {
        return Status::InvalidArgument("served pair out of range (0 <= a < b < 180)");
      }
      const size_t slot = static_cast<size_t>(choice.a) * 180 + static_cast<size_t>(choice.b);
      return Lookup{sections.pairs, TableSpace::kTwoDirections, slot, &ServedTwo()[slot]};
    }
  }
  return Status::InvalidArgument("unknown choice");
}

}  // namespace

bool SetTable::Holds(const Sections& sections, const SetChoice& choice) const {
  auto at = Locate(sections, choice);
  return at.ok() && at->section != nullptr && at->section->Holds(*at->served);
}

StatusOr<TableSet> SetTable::Find(const Sections& sections, const SetChoice& choice) const {
  auto at = Locate(sections, choice);
  if (!at.ok()) return at.status();
  if (at->section != nullptr && at->section->Holds(*at->served)) return at->section->Aligned(at->slot, *at->served);
  const std::string n = std::to_string(sections.n), c(sections.construction);
  std::string what = TableSpaceName(at->space);
  if (at->section != nullptr) {
    what += choice.kind == SetChoice::Kind::kTwo
                ? " pair (" + std::to_string(choice.a) + ", " + std::to_string(choice.b) + ")"
                : " direction " + std::to_string(choice.a);
    what += " (its section holds only some keys)";
  }
  return Status::NotFound("the table has no " + c + " sets of N = " + n + " for " + what +
                          " (export them: alignset export --n " + n + " --construction " + c + ")");
}

StatusOr<TableSet> SetTable::FindOne(uint32_t n, std::string_view construction, double theta_deg) const {
  if (!std::isfinite(theta_deg)) return Status::InvalidArgument("direction is not a finite number");
  if (const Section* e = impl_->Find(n, construction, TableSpace::kOneQuarter)) {
    double t = std::fmod(theta_deg, 180.0);
    if (t < 0) t += 180.0;
    const size_t q = static_cast<size_t>(std::llround(t * 4.0)) % 720;
    const Served& served = ServedOne(AngleGrid::kQuarterDegree)[q];
    if (e->Holds(served)) return e->Aligned(q, served);
    return Status::NotFound("the table has no " + std::string(construction) + " sets of N = " + std::to_string(n) +
                            " for direction " + std::to_string(theta_deg) +
                            " (its quarter-degree section holds only some keys)");
  }
  return Find(n, construction, {SetChoice::Kind::kOne, ServedDegree(theta_deg), 0});
}

}  // namespace alignset
