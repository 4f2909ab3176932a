// The key lineage: a key that is not a root continues from its parent's set
// (core/align/key_lineage.h), and still its set is a function of its key.
// Real servers on loopback, each on its own SQLite file: the same key filled
// cold (its whole lineage computed in one job), after its neighbours, in a
// batch precompute in another order, in one shard of the two-direction
// space, lazily from a file a previous server left, and in another
// request order gives the same bytes. With --warm-budget 0 (a profile of
// its own), and below --warm-min-n, every key is optimized from Owen-Sobol.
#include <gtest/gtest.h>

#include <alignset/client.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/align/canonical.h"
#include "core/align/key_lineage.h"
#include "tests/e2e/server_process.h"

namespace alignset::e2e {
namespace {

const std::vector<std::string> kCold = {"--max-iterations", "60", "--workers", "1",
                                        "--threads-per-worker", "1", "--max-n", "4096"};
// The server's default warm budget (the harness turns it off), and the
// lineage down to the smallest N so that these tests run in seconds.
const std::vector<std::string> kFlags = [] {
  std::vector<std::string> f = kCold;
  const std::vector<std::string> warm = DefaultWarmBudgetFlags();
  f.insert(f.end(), warm.begin(), warm.end());
  f.insert(f.end(), {"--warm-min-n", "16"});
  return f;
}();
// The same with two workers of one thread: two keys side by side.
const std::vector<std::string> kTwoWorkerFlags = [] {
  std::vector<std::string> f = kFlags;
  for (size_t i = 0; i + 1 < f.size(); ++i) {
    if (f[i] == "--workers") f[i + 1] = "2";
  }
  return f;
}();
constexpr uint32_t kN = 64;

AlignedSet MustGet(ServiceClient& client, std::vector<double> dirs) {
  alignset::SetRequest r;
  r.n = kN;
  r.directions_deg = std::move(dirs);
  auto s = client.GetAlignedSet(r);
  EXPECT_TRUE(s.ok()) << s.status().message();
  return s.ok() ? std::move(s).value() : AlignedSet{};
}

// A fresh folder under the test's one: one server, one cache file.
std::string Folder(const TempDir& dir, const std::string& name) {
  const std::string path = dir.path() + "/" + name;
  std::filesystem::create_directories(path);
  return path;
}

bool SameBytes(const PointSet& a, const PointSet& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].x != b[i].x || a[i].y != b[i].y) return false;
  }
  return true;
}

void Precompute(ServiceClient& client, const PrecomputeSpec& spec) {
  auto done = client.Precompute(spec, nullptr);
  ASSERT_TRUE(done.ok()) << done.status().message();
  EXPECT_EQ(done->failed, 0u);
}

// A precompute of the one-direction space at `sizes` on a fresh two-worker
// server: each optimized key as (N, degrees), in the order they completed.
std::vector<std::pair<uint32_t, int>> TwoWorkerCompletionOrder(const TempDir& dir,
                                                               std::vector<uint32_t> sizes) {
  std::vector<std::pair<uint32_t, int>> completed;
  ServerProcess server(Folder(dir, "two"), kTwoWorkerFlags);
  EXPECT_TRUE(server.error().empty()) << server.error();
  auto client = ConnectTo(server);
  if (client == nullptr) {
    ADD_FAILURE() << "no connection";
    return completed;
  }
  PrecomputeSpec spec;
  spec.n = std::move(sizes);
  spec.space = 1;
  uint64_t done = 0;
  auto result = client->Precompute(spec, [&](const PrecomputeUpdate& u) {
    if (u.done == done) return;
    done = u.done;
    // "n=N dirs=1:D profile=..." (storage::KeyToString)
    const size_t at = u.last_key.find(" dirs=1:");
    ASSERT_TRUE(u.last_key.rfind("n=", 0) == 0 && at != std::string::npos) << u.last_key;
    completed.emplace_back(static_cast<uint32_t>(std::stoul(u.last_key.substr(2))),
                           std::stoi(u.last_key.substr(at + 8)));
  });
  EXPECT_TRUE(result.ok()) << result.status().message();
  return completed;
}

// The shard of `shards` whose block of the lineage order (roots' subtrees
// one after another, each by depth; the server's precompute order) holds
// the key at canonical `index` of the count-direction space.
uint32_t ShardOf(size_t index, int count, uint32_t shards) {
  const size_t size = CanonicalKeyCount(count);
  std::vector<std::tuple<size_t, int, size_t>> order;
  for (size_t i = 0; i < size; ++i) {
    const CanonicalDirections key = CanonicalKeyAt(count, i);
    order.emplace_back(*CanonicalKeyIndex(LineageRoot(key)), LineageDepth(key), i);
  }
  std::sort(order.begin(), order.end());
  for (size_t p = 0; p < size; ++p) {
    if (std::get<2>(order[p]) != index) continue;
    for (uint32_t k = 0; k < shards; ++k) {
      if (p < size * (k + 1) / shards) return k;
    }
  }
  return 0;
}

// The canonical key (33, 57): depth 3 (the deepest there is), its lineage
// runs from the root (31, 58) through (31, 57) and (32, 57).
const std::vector<double> kKey = {33, 57};
const std::vector<double> kRoot = {31, 58};

// The directions of the key's parent (generation 1), grandparent (2), ...
std::vector<double> Ancestor(const std::vector<double>& key, int generation) {
  CanonicalDirections k = Canonicalize(key)->key;
  for (int g = 0; g < generation; ++g) k = WarmParent(k)->parent;
  return {Phi1Degrees(k), Phi2Degrees(k)};
}

TEST(Lineage, TheTestKeyIsDeepEnoughToMatter) {
  const auto c = Canonicalize(kKey);
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(LineageDepth(c->key), 3);
  EXPECT_EQ(LineageRoot(c->key), Canonicalize(kRoot)->key);
  EXPECT_EQ(Ancestor(kKey, 2), (std::vector<double>{31, 57}));  // as the batch below says
}

TEST(Lineage, AKeysSetIsTheSameWhateverWasFilledBefore) {
  TempDir dir;
  // 1: cold, the whole lineage in one job.
  PointSet cold;
  {
    ServerProcess server(Folder(dir, "cold"), kFlags);
    ASSERT_TRUE(server.error().empty()) << server.error();
    auto client = ConnectTo(server);
    ASSERT_NE(client, nullptr);
    const AlignedSet set = MustGet(*client, kKey);
    EXPECT_FALSE(set.info.from_cache);
    cold = set.points;
    ASSERT_EQ(cold.size(), kN);
    auto stats = client->GetMetrics();
    ASSERT_TRUE(stats.ok());
    // The key and the ancestors it needed were optimized, once each.
    EXPECT_EQ(stats->optimizations_completed, static_cast<uint64_t>(LineageDepth(Canonicalize(kKey)->key)) + 1);
  }
  // 2: after its parent and grandparent, through another orientation of
  // the same key.
  {
    ServerProcess server(Folder(dir, "neighbours"), kFlags);
    ASSERT_TRUE(server.error().empty()) << server.error();
    auto client = ConnectTo(server);
    ASSERT_NE(client, nullptr);
    MustGet(*client, Ancestor(kKey, 1));
    MustGet(*client, Ancestor(kKey, 2));
    const AlignedSet set = MustGet(*client, {57, 33});
    // The same orbit representative, reached with no swap or mirror.
    EXPECT_FALSE(set.info.swapped || set.info.inverted || set.info.inverted_y);
    EXPECT_TRUE(SameBytes(set.points, cold)) << "after its neighbours";
  }
  // 3: a batch precompute in another order (the key before its grandparent).
  {
    ServerProcess server(Folder(dir, "batch"), kFlags);
    ASSERT_TRUE(server.error().empty()) << server.error();
    auto client = ConnectTo(server);
    ASSERT_NE(client, nullptr);
    PrecomputeSpec spec;
    spec.n = {kN};
    spec.space = 0;
    // The key listed before its grandparent, and two unrelated keys.
    spec.keys = {{33, 57}, {10, 20}, {31, 57}, {30, 60}};
    Precompute(*client, spec);
    const AlignedSet set = MustGet(*client, kKey);
    EXPECT_TRUE(set.info.from_cache);
    EXPECT_TRUE(SameBytes(set.points, cold)) << "in a batch, listed before its grandparent";
  }
  // 4: the shard of the two-direction space that holds the key, then the
  // file the shard's server left, read by a new server.
  const auto index = CanonicalKeyIndex(Canonicalize(kKey)->key);
  ASSERT_TRUE(index.ok());
  const uint32_t shards = 97;
  {
    ServerProcess server(Folder(dir, "shard"), kFlags);
    ASSERT_TRUE(server.error().empty()) << server.error();
    auto client = ConnectTo(server);
    ASSERT_NE(client, nullptr);
    PrecomputeSpec spec;
    spec.n = {kN};
    spec.space = 2;
    spec.shard_index = ShardOf(*index, 2, shards);
    spec.shard_count = shards;
    Precompute(*client, spec);
    const AlignedSet set = MustGet(*client, kKey);
    EXPECT_TRUE(set.info.from_cache);
    EXPECT_TRUE(SameBytes(set.points, cold)) << "in shard " << spec.shard_index << "/" << shards;
  }
  {
    ServerProcess server(Folder(dir, "shard"), kFlags);
    ASSERT_TRUE(server.error().empty()) << server.error();
    auto client = ConnectTo(server);
    ASSERT_NE(client, nullptr);
    const AlignedSet set = MustGet(*client, kKey);
    EXPECT_TRUE(set.info.from_cache);
    EXPECT_TRUE(SameBytes(set.points, cold)) << "read back by a new server";
    // A key of another root's subtree, outside the shard: optimized on
    // request.
    const AlignedSet far = MustGet(*client, {33, 47});
    EXPECT_FALSE(far.info.from_cache);
  }
}

// Shards hold contiguous blocks of the lineage order, parents before
// children: run one after another on one server, every shard finds its
// keys' parents stored (by itself or an earlier shard), so no item is
// found cached and every key is optimized exactly once.
TEST(Lineage, ShardsPartitionTheLineageOrderAndFindTheirParents) {
  TempDir dir;
  ServerProcess server(Folder(dir, "shards"), kFlags);
  ASSERT_TRUE(server.error().empty()) << server.error();
  auto client = ConnectTo(server);
  ASSERT_NE(client, nullptr);
  uint64_t total = 0, done = 0, cached = 0;
  for (uint32_t k = 0; k < 7; ++k) {
    PrecomputeSpec spec;
    spec.n = {kN};
    spec.space = 1;
    spec.shard_index = k;
    spec.shard_count = 7;
    auto r = client->Precompute(spec, nullptr);
    ASSERT_TRUE(r.ok()) << r.status().message();
    total += r->total;
    done += r->done;
    cached += r->cached_already;
  }
  EXPECT_EQ(total, 46u);
  EXPECT_EQ(done, 46u);
  EXPECT_EQ(cached, 0u);
  auto stats = client->GetMetrics();
  ASSERT_TRUE(stats.ok());
  EXPECT_EQ(stats->optimizations_completed, 46u);
}

// With two workers a batch runs two keys side by side, and a key waits
// while its parent is still running in the batch: every key is still
// optimized exactly once (a job that started before its parent was stored
// would optimize that parent again as its ancestor), and every set is the
// one a single worker makes.
TEST(Lineage, TwoWorkersFillTheSpaceOnceWithTheSameSets) {
  TempDir dir;
  ServerProcess one(Folder(dir, "one"), kFlags);
  ASSERT_TRUE(one.error().empty()) << one.error();
  ServerProcess two(Folder(dir, "two"), kTwoWorkerFlags);
  ASSERT_TRUE(two.error().empty()) << two.error();
  auto a = ConnectTo(one);
  auto b = ConnectTo(two);
  ASSERT_NE(a, nullptr);
  ASSERT_NE(b, nullptr);
  PrecomputeSpec spec;
  spec.n = {kN};
  spec.space = 1;
  Precompute(*a, spec);
  Precompute(*b, spec);
  for (ServiceClient* client : {a.get(), b.get()}) {
    auto stats = client->GetMetrics();
    ASSERT_TRUE(stats.ok());
    EXPECT_EQ(stats->optimizations_completed, 46u);
  }
  for (int deg = 0; deg <= 45; ++deg) {
    const AlignedSet x = MustGet(*a, {static_cast<double>(deg)});
    const AlignedSet y = MustGet(*b, {static_cast<double>(deg)});
    EXPECT_TRUE(x.info.from_cache && y.info.from_cache) << deg;
    EXPECT_TRUE(SameBytes(x.points, y.points)) << deg;
  }
}

// Two workers start every root (a cold optimization, several warm steps
// long) before any warm key, so that a batch ends on short warm steps
// rather than on a root running alone. Nothing but roots has been started
// until the last root has, which takes roots - 2 completions; so the first
// roots - 1 keys to complete are roots. Taking a ready child before the next
// root (the order before) finishes warm children among the first few.
TEST(Lineage, TwoWorkersStartEveryRootBeforeAWarmKey) {
  TempDir dir;
  const auto completed = TwoWorkerCompletionOrder(dir, {kN});
  ASSERT_EQ(completed.size(), 46u);
  int roots = 0;
  for (int deg = 0; deg <= 45; ++deg) roots += LineageDepth(CanonicalKeyAt(1, deg)) == 0;
  ASSERT_GE(roots, 3);
  for (int i = 0; i + 1 < roots; ++i) {
    const int deg = completed[i].second;
    EXPECT_EQ(LineageDepth(CanonicalKeyAt(1, static_cast<size_t>(deg))), 0)
        << "completion " << i << " is the warm key at " << deg << " degrees";
  }
}

// Roots first holds within one N: a request for two sizes starts the second
// size's keys only when every key of the first has started, so at most one
// key of the first completes after the second size's first key. Reading
// ahead for roots across sizes would start the larger size's roots while the
// smaller size's warm keys wait.
TEST(Lineage, TwoWorkersFinishOneSizeBeforeTheNext) {
  TempDir dir;
  const auto completed = TwoWorkerCompletionOrder(dir, {kN, 4 * kN});
  ASSERT_EQ(completed.size(), 92u);
  const auto first_large = std::find_if(completed.begin(), completed.end(),
                                        [](const auto& c) { return c.first == 4 * kN; }) -
                           completed.begin();
  EXPECT_GE(first_large, 45) << "a key of N = " << 4 * kN << " completed before "
                             << first_large << " of the 46 keys of N = " << kN;
  EXPECT_EQ(std::count_if(completed.begin(), completed.end(), [](const auto& c) { return c.first == kN; }),
            46);
}

TEST(Lineage, WarmBudgetZeroOptimizesEveryKeyColdUnderItsOwnProfile) {
  TempDir dir;
  std::vector<std::string> flags = kCold;
  flags.insert(flags.end(), {"--warm-budget", "0"});
  ServerProcess cold_server(Folder(dir, "cold"), flags);
  ASSERT_TRUE(cold_server.error().empty()) << cold_server.error();
  ServerProcess warm_server(Folder(dir, "warm"), kFlags);
  ASSERT_TRUE(warm_server.error().empty()) << warm_server.error();
  auto cold = ConnectTo(cold_server);
  auto warm = ConnectTo(warm_server);
  ASSERT_NE(cold, nullptr);
  ASSERT_NE(warm, nullptr);
  const AlignedSet a = MustGet(*cold, kKey);
  const AlignedSet b = MustGet(*warm, kKey);
  EXPECT_NE(a.info.profile, b.info.profile);
  EXPECT_FALSE(SameBytes(a.points, b.points));
  EXPECT_EQ(a.info.iterations, 60);  // the cold budget (--max-iterations)
  EXPECT_EQ(b.info.iterations, 8);  // the warm one: 0.13 of it
  auto stats = cold->GetMetrics();
  ASSERT_TRUE(stats.ok());
  EXPECT_EQ(stats->optimizations_completed, 1u);
  // A root is optimized cold by both: the same set under two profiles.
  const AlignedSet ra = MustGet(*cold, kRoot);
  const AlignedSet rb = MustGet(*warm, kRoot);
  EXPECT_TRUE(SameBytes(ra.points, rb.points));
}

TEST(Lineage, BelowWarmMinNEveryKeyIsCold) {
  TempDir dir;
  std::vector<std::string> flags = kCold;
  const std::vector<std::string> warm = DefaultWarmBudgetFlags();
  flags.insert(flags.end(), warm.begin(), warm.end());  // --warm-min-n at its default, 4096
  ServerProcess server(Folder(dir, "small"), flags);
  ASSERT_TRUE(server.error().empty()) << server.error();
  auto client = ConnectTo(server);
  ASSERT_NE(client, nullptr);
  const AlignedSet set = MustGet(*client, kKey);
  EXPECT_EQ(set.info.iterations, 60);
  auto stats = client->GetMetrics();
  ASSERT_TRUE(stats.ok());
  EXPECT_EQ(stats->optimizations_completed, 1u);
}

TEST(Lineage, TheServerRefusesABadWarmBudgetOrMinN) {
  TempDir dir;
  for (const char* bad : {"-0.1", "1.5", "nan", "x"}) {
    std::vector<std::string> flags = kFlags;
    flags.insert(flags.end(), {"--warm-budget", bad});
    ServerProcess server(Folder(dir, "bad"), flags);
    EXPECT_FALSE(server.error().empty()) << bad;
  }
  for (const char* bad : {"8", "-1", "x"}) {
    std::vector<std::string> flags = kFlags;
    flags.insert(flags.end(), {"--warm-min-n", bad});
    ServerProcess server(Folder(dir, "bad"), flags);
    EXPECT_FALSE(server.error().empty()) << bad;
  }
}

}  // namespace
}  // namespace alignset::e2e
