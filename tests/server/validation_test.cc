#include "server/validation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

#include "core/optimize/aligned_lattice.h"
#include "server/canonical_entry.h"
#include "server/config.h"
#include "server/set_lru.h"

namespace alignset::server {
namespace {

void ExpectInvalid(uint32_t n, std::vector<double> dirs, const std::string& fragment) {
  auto r = ValidateAlignedSetRequest(n, dirs, 4096);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Status::Code::kInvalidArgument);
  EXPECT_NE(r.status().message().find(fragment), std::string::npos) << r.status().message();
}

TEST(Validation, RefusesEachBadFieldWithAMessageNamingIt) {
  ExpectInvalid(0, {30}, "N = 0 is below the minimum of 16 points (missing?)");
  ExpectInvalid(15, {30}, "below the minimum");
  ExpectInvalid(4097, {30}, "maximum of 4096");
  ExpectInvalid(64, {}, "one or two directions");
  ExpectInvalid(64, {1, 2, 3}, "got 3");
  ExpectInvalid(64, {std::nan("")}, "not a finite");
  ExpectInvalid(64, {10, std::numeric_limits<double>::infinity()}, "direction 1");
  ExpectInvalid(64, {1e300}, "= 1e+300 degrees is too large");
}

TEST(Validation, AcceptsAndCanonicalizes) {
  auto r = ValidateAlignedSetRequest(4096, {120.2}, 4096);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(r->key.count, 1);
  EXPECT_EQ(r->key.phi1, 30);
  EXPECT_TRUE(r->ops.swap);
  EXPECT_TRUE(r->ops.invert);
  ASSERT_EQ(r->served_deg.size(), 1u);
  EXPECT_EQ(r->served_deg[0], 120);
}

TEST(Config, FlagsOverrideEnvironmentOverridesDefaults) {
  std::map<std::string, std::string> env = {{"ALIGNSET_WORKERS", "3"}, {"ALIGNSET_MAX_N", "1024"}};
  auto lookup = [&](const char* name) -> const char* {
    auto it = env.find(name);
    return it == env.end() ? nullptr : it->second.c_str();
  };
  std::vector<std::string> argv_s = {"--workers", "5", "--listen=0.0.0.0:1", "--engine", "direct"};
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  auto c = ParseServerConfig(static_cast<int>(argv.size()), argv.data(), lookup);
  ASSERT_TRUE(c.ok()) << c.status().message();
  EXPECT_EQ(c->workers, 5);
  EXPECT_EQ(c->max_n, 1024u);
  EXPECT_EQ(c->listen, "0.0.0.0:1");
  EXPECT_EQ(c->engine, EngineKind::kDirect);
  EXPECT_EQ(c->max_iterations, 0);
}

TEST(Config, RefusesBadValues) {
  auto parse = [](std::vector<std::string> a) {
    std::vector<char*> argv;
    for (auto& s : a) argv.push_back(s.data());
    return ParseServerConfig(static_cast<int>(argv.size()), argv.data(), nullptr);
  };
  EXPECT_FALSE(parse({"--workers", "0"}).ok());
  EXPECT_FALSE(parse({"--max-n", "8"}).ok());
  EXPECT_FALSE(parse({"--engine", "gpu"}).ok());
  EXPECT_FALSE(parse({"--bogus", "1"}).ok());
  EXPECT_FALSE(parse({"--workers"}).ok());
  EXPECT_FALSE(parse({"--tls-cert", "a.pem"}).ok());  // without --tls-key
  EXPECT_EQ(parse({"--help"}).status().code(), Status::Code::kNotFound);
}

storage::SetRecord Record(uint32_t n, int phi) {
  storage::SetRecord r;
  r.key = {n, {1, phi, phi}, "p"};
  r.points.resize(n, Point2{0.25, 0.5});
  return r;
}

TEST(Config, DefaultThreadsShareTheCoresAmongWorkers) {
  EXPECT_EQ(ThreadsPerWorker(1, 0, 8), 8);
  EXPECT_EQ(ThreadsPerWorker(2, 0, 8), 4);
  EXPECT_EQ(ThreadsPerWorker(3, 0, 8), 2);
  EXPECT_EQ(ThreadsPerWorker(16, 0, 8), 1);  // never zero
  EXPECT_EQ(ThreadsPerWorker(2, 0, 0), 1);   // core count unknown
  EXPECT_EQ(ThreadsPerWorker(2, 5, 8), 5);   // an explicit setting wins
}

TEST(SetLru, EvictsLeastRecentlyUsedByBytes) {
  const size_t one = CanonicalEntry(Record(64, 0)).ChargedBytes();
  SetLru lru(3 * one);
  for (int phi = 0; phi < 3; ++phi) {
    lru.Put("k" + std::to_string(phi), std::make_shared<CanonicalEntry>(Record(64, phi)));
  }
  ASSERT_NE(lru.Get("k0"), nullptr);  // k1 is now the oldest
  lru.Put("k3", std::make_shared<CanonicalEntry>(Record(64, 3)));
  EXPECT_EQ(lru.size(), 3u);
  EXPECT_EQ(lru.Get("k1"), nullptr);
  EXPECT_NE(lru.Get("k0"), nullptr);
  EXPECT_NE(lru.Get("k3"), nullptr);
  EXPECT_LE(lru.bytes(), 3 * one);
}

TEST(CanonicalEntry, EncodesAlignedPointsAsLittleEndianPairs) {
  storage::SetRecord r;
  r.points = {{0.25, 0.125}, {0.5, 0.75}};
  CanonicalEntry e(r);
  const std::string plain = *e.Encoded({});
  ASSERT_EQ(plain.size(), 32u);
  double v[4];
  std::memcpy(v, plain.data(), 32);
  EXPECT_EQ(v[0], 0.25);
  EXPECT_EQ(v[1], 0.125);
  EXPECT_EQ(v[3], 0.75);
  const std::string swapped = *e.Encoded({.swap = true});
  std::memcpy(v, swapped.data(), 32);
  EXPECT_EQ(v[0], 0.125);
  EXPECT_EQ(v[1], 0.25);
  EXPECT_EQ(e.Encoded({.swap = true}).get(), e.Encoded({.swap = true}).get());  // built once
}

// A lattice entry tells its generator from its points; an entry whose points
// are no lattice of its realization tells none (and is still served).
TEST(CanonicalEntry, ReadsALatticesGeneratorBackFromItsPoints) {
  for (bool folded : {false, true}) {
    storage::SetRecord lattice;
    lattice.points = LatticePoints(256, 77, 5, folded);
    const CanonicalEntry e(lattice);
    EXPECT_EQ(e.LatticeGenerator(5, folded), std::optional<uint32_t>(77u));
    EXPECT_EQ(e.LatticeGenerator(5, folded), std::optional<uint32_t>(77u));  // read once, kept
    storage::SetRecord other;
    other.points = LatticePoints(256, 77, 6, folded);  // realization 6's points
    EXPECT_FALSE(CanonicalEntry(other).LatticeGenerator(5, folded).has_value());
    EXPECT_EQ(*CanonicalEntry(other).Encoded({}), EncodePoints(other.points));
  }
}

}  // namespace
}  // namespace alignset::server

namespace alignset::server {
namespace {

TEST(Validation, BatchSizeIsBounded) {
  EXPECT_TRUE(ValidateBatchSize(1, 64).ok());
  EXPECT_TRUE(ValidateBatchSize(kMaxBatchItems, kMaxBatchPoints).ok());
  EXPECT_EQ(ValidateBatchSize(0, 0).code(), Status::Code::kInvalidArgument);
  EXPECT_EQ(ValidateBatchSize(kMaxBatchItems + 1, 64).code(), Status::Code::kInvalidArgument);
  EXPECT_EQ(ValidateBatchSize(2, kMaxBatchPoints + 1).code(), Status::Code::kInvalidArgument);
}

}  // namespace
}  // namespace alignset::server
