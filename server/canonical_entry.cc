#include "server/canonical_entry.h"

#include <bit>
#include <cstring>

#include <spdlog/spdlog.h>

#include "core/optimize/aligned_lattice.h"

namespace alignset::server {

static_assert(std::endian::native == std::endian::little,
              "the wire format is little-endian float64; add a byte swap for this host");
static_assert(sizeof(Point2) == 2 * sizeof(double), "Point2 must be two packed doubles");

std::string EncodePoints(const PointSet& points) {
  std::string out(points.size() * sizeof(Point2), '\0');
  if (!points.empty()) std::memcpy(out.data(), points.data(), out.size());
  return out;
}

namespace {
size_t OpsIndex(const AlignOps& ops) {
  return (ops.swap ? 4 : 0) + (ops.invert ? 2 : 0) + (ops.invert_y ? 1 : 0);
}
}  // namespace

std::shared_ptr<const std::string> CanonicalEntry::Encoded(const AlignOps& ops) const {
  const size_t i = OpsIndex(ops);
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (encoded_[i]) return encoded_[i];
  }
  // Built outside the lock: two racing requests may both build it, which is
  // harmless and cheaper than serializing every alignment behind one mutex.
  auto bytes = std::make_shared<const std::string>(EncodePoints(Align(record_.points, ops)));
  std::lock_guard<std::mutex> lock(mu_);
  if (!encoded_[i]) encoded_[i] = std::move(bytes);
  return encoded_[i];
}

std::optional<uint32_t> CanonicalEntry::LatticeGenerator(uint64_t seed, bool folded) const {
  std::lock_guard<std::mutex> lock(mu_);
  if (!generator_read_) {
    generator_ = LatticeGeneratorOf(record_.points, seed, folded);
    generator_read_ = true;
    // Once per entry, not per request: the set is still served, without
    // its generator (lattice_generator 0).
    if (!generator_) {
      spdlog::warn("{}: the cached points are not the lattice of any generator",
                   storage::KeyToString(record_.key));
    }
  }
  return generator_;
}

}  // namespace alignset::server
