// Where a key's set comes from, apart from the queue: memory, SQLite, a
// construction, a writer (replica), and the key lineage's plan.
#include "server/set_producer.h"

#include <gtest/gtest.h>

#include "core/align/key_lineage.h"
#include "core/optimize/construction.h"
#include "tests/storage/test_util.h"

namespace alignset::server {
namespace {

class SetProducerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    cache_ = storage::testing::MustOpen(dir_.File("cache.sqlite"));
    ASSERT_NE(cache_, nullptr);
  }
  void TearDown() override {
    producer_.reset();
    cache_.reset();
  }
  void Start(SetProducer::Options o = {}) {
    auto p = SetProducer::Create(o, cache_.get(), &metrics_);
    ASSERT_TRUE(p.ok()) << p.status().message();
    producer_ = std::move(p).value();
  }
  storage::SetRecord Record(const storage::SetKey& key) {
    storage::SetRecord r;
    r.key = key;
    for (uint32_t i = 0; i < key.n; ++i) r.points.push_back({(i + 0.5) / key.n, (i * 7 % key.n + 0.5) / key.n});
    r.engine = "test";
    return r;
  }

  storage::testing::TempDir dir_;
  std::unique_ptr<storage::SetCache> cache_;
  Metrics metrics_;
  std::unique_ptr<SetProducer> producer_;
};

TEST_F(SetProducerTest, KeysCarryTheirConstructionsProfile) {
  Start();
  const CanonicalDirections dirs{1, 30, 30};
  for (const Construction& c : Constructions()) {
    const storage::SetKey key = producer_->KeyFor(256, dirs, 3, c.kind);
    EXPECT_EQ(key.n, 256u);
    EXPECT_EQ(key.realization, 3u);
    if (c.optimized()) {
      EXPECT_EQ(key.profile, storage::ProfileId(DefaultFrequencyParams(256), OptimizerOptions{}, 1));
    } else {
      EXPECT_EQ(key.profile, c.profile);
    }
    EXPECT_EQ(&ConstructionOfProfile(key.profile), &c);
  }
}

TEST_F(SetProducerTest, ACompletedSetIsStoredThenServedFromMemoryThenFromTheCache) {
  Start();
  const storage::SetKey key = producer_->KeyFor(64, {1, 10, 10}, 0, ConstructionKind::kOptimized);
  const std::string name = KeyString(key);
  EXPECT_EQ(producer_->FromMemory(name, key, true), nullptr);
  EXPECT_EQ(producer_->FromCache(name, key).status().code(), Status::Code::kNotFound);
  EXPECT_FALSE(producer_->IsStored(key).value());

  auto entry = producer_->Complete(name, Record(key));
  EXPECT_TRUE(entry->stored());
  EXPECT_GT(entry->record().created_unix, 0);
  EXPECT_TRUE(producer_->IsStored(key).value());
  EXPECT_EQ(metrics_.optimizations_completed.load(), 1u);
  auto hit = producer_->FromMemory(name, key, true);
  ASSERT_NE(hit, nullptr);
  EXPECT_EQ(hit->record().points, Record(key).points);
  EXPECT_EQ(metrics_.cache_hits_memory.load(), 1u);

  // A second producer on the same file has nothing in memory: SQLite serves it.
  producer_.reset();
  Start();
  EXPECT_EQ(producer_->FromMemory(name, key, true), nullptr);
  auto stored = producer_->FromCache(name, key);
  ASSERT_TRUE(stored.ok()) << stored.status().message();
  EXPECT_EQ((*stored)->record().points, Record(key).points);
  EXPECT_EQ(metrics_.cache_hits_db.load(), 1u);
  EXPECT_NE(producer_->FromMemory(name, key, false), nullptr);  // kept in memory since
}

TEST_F(SetProducerTest, AConstructedKeyIsItsConstructionsSetStoredUnderItsName) {
  SetProducer::Options o;
  o.threads_per_worker = 1;
  Start(o);
  for (ConstructionKind kind : {ConstructionKind::kLattice, ConstructionKind::kTentLattice, ConstructionKind::kNet}) {
    const Construction& c = ConstructionOf(kind);
    const storage::SetKey key = producer_->KeyFor(256, {2, 12, 77}, 2, kind);
    double seconds = -1.0;
    auto built = producer_->Construct(KeyString(key), key, &seconds);
    ASSERT_TRUE(built.ok()) << built.status().message();
    EXPECT_GE(seconds, 0.0);
    EXPECT_EQ((*built)->record().engine, c.name);
    auto direct = c.Build(256, {12.0, 77.0}, 2);
    ASSERT_TRUE(direct.ok());
    EXPECT_EQ((*built)->record().points, direct->points) << c.name;
    EXPECT_TRUE(cache_->Contains(key).value());
  }
  // A construction that cannot make the key is an internal error naming it.
  const storage::SetKey bad = producer_->KeyFor(100, {1, 30, 30}, 0, ConstructionKind::kNet);
  double seconds = 0.0;
  auto failed = producer_->Construct(KeyString(bad), bad, &seconds);
  EXPECT_EQ(failed.status().code(), Status::Code::kInternal);
  EXPECT_NE(failed.status().message().find("net construction failed"), std::string::npos);
  EXPECT_EQ(metrics_.optimizations_failed.load(), 1u);
}

TEST_F(SetProducerTest, AReplicaKeepsWhatItsWriterSendsInMemoryOnly) {
  SetProducer::Options o;
  o.read_only = true;
  int asked = 0;
  o.fill = [&](const storage::SetKey& key, const std::function<bool()>&) -> StatusOr<storage::SetRecord> {
    ++asked;
    if (key.n == 128) return Status::NotFound("the writer has none");
    return Record(key);
  };
  Start(o);
  const storage::SetKey key = producer_->KeyFor(64, {1, 20, 20}, 0, ConstructionKind::kOptimized);
  auto filled = producer_->Fill(KeyString(key), key, [] { return false; });
  ASSERT_TRUE(filled.ok());
  EXPECT_FALSE((*filled)->stored());
  EXPECT_FALSE(cache_->Contains(key).value());
  EXPECT_NE(producer_->FromMemory(KeyString(key), key, false), nullptr);
  EXPECT_EQ(metrics_.sets_filled.load(), 1u);
  const storage::SetKey missing = producer_->KeyFor(128, {1, 20, 20}, 0, ConstructionKind::kOptimized);
  EXPECT_EQ(producer_->Fill(KeyString(missing), missing, [] { return false; }).status().code(), Status::Code::kNotFound);
  EXPECT_EQ(asked, 2);
  // A read-only producer never writes, even a set it completed.
  auto done = producer_->Complete(KeyString(missing), Record(missing));
  EXPECT_FALSE(done->stored());
  EXPECT_FALSE(cache_->Contains(missing).value());
}

TEST_F(SetProducerTest, TheLineagePlanStartsAtARootOrAtAHeldParent) {
  Start();  // the default warm budget: keys of N >= 4096 use the lineage
  // A key two steps from its root (one direction: roots at 1, 8, 15, ...).
  const storage::SetKey key = producer_->KeyFor(4096, {1, 10, 10}, 0, ConstructionKind::kOptimized);
  LineagePlan cold = producer_->PlanLineage(KeyString(key), key);
  ASSERT_GE(cold.chain.size(), 2u);
  EXPECT_EQ(KeyString(cold.chain.back()), KeyString(key));
  EXPECT_FALSE(producer_->LineageParentKey(cold.chain.front()).has_value());  // a root
  EXPECT_FALSE(cold.warm_start.has_value());
  for (size_t i = 1; i < cold.chain.size(); ++i) {
    EXPECT_EQ(KeyString(*producer_->LineageParentKey(cold.chain[i])), KeyString(cold.chain[i - 1]));
  }
  // With the parent held, the plan is the key alone, from the parent's set aligned.
  const storage::SetKey parent = *producer_->LineageParentKey(key);
  producer_->Complete(KeyString(parent), Record(parent));
  LineagePlan warm = producer_->PlanLineage(KeyString(key), key);
  ASSERT_EQ(warm.chain.size(), 1u);
  ASSERT_TRUE(warm.warm_start.has_value());
  EXPECT_EQ(*warm.warm_start, Align(Record(parent).points, WarmParent(key.dirs)->ops));
  EXPECT_LT(warm.iterations_total, cold.iterations_total);
  // Constructed keys and small N have no lineage.
  EXPECT_FALSE(producer_->LineageParentKey(producer_->KeyFor(4096, {1, 10, 10}, 0, ConstructionKind::kLattice)));
  EXPECT_FALSE(producer_->LineageParentKey(producer_->KeyFor(1024, {1, 10, 10}, 0, ConstructionKind::kOptimized)));
}

}  // namespace
}  // namespace alignset::server
