// The construction of a served set: the names a request may give, the
// lattice's own profile, and a lattice key's job in the scheduler (computed
// without the spectral engine, stored like an optimized set).
#include "server/construction.h"

#include <gtest/gtest.h>

#include "core/align/canonical.h"
#include "core/optimize/aligned_lattice.h"
#include "server/scheduler.h"
#include "tests/server/scheduler_fixture.h"

namespace alignset::server {
namespace {

TEST(Construction, NamesParseAndUnknownOnesListTheKnown) {
  EXPECT_EQ(ParseConstruction("").value()->kind, ConstructionKind::kOptimized);
  EXPECT_EQ(ParseConstruction("optimized").value()->kind, ConstructionKind::kOptimized);
  EXPECT_EQ(ParseConstruction("lattice").value()->kind, ConstructionKind::kLattice);
  EXPECT_EQ(ParseConstruction("net").value()->kind, ConstructionKind::kNet);
  for (const char* bad : {"Lattice", "sobol", " lattice", "optimised", "nets"}) {
    auto c = ParseConstruction(bad);
    ASSERT_FALSE(c.ok()) << bad;
    EXPECT_EQ(c.status().code(), Status::Code::kInvalidArgument);
    EXPECT_EQ(c.status().message(), "unknown construction '" + std::string(bad) +
                                        "': the known ones are 'optimized' (the default, also ''), "
                                        "'lattice', 'tent-lattice', 'net' and 'lattice-sequence'");
  }
  // A client's name is escaped and cut, never echoed raw.
  auto forged = ParseConstruction("x\nforged" + std::string(1000, 'a'));
  ASSERT_FALSE(forged.ok());
  EXPECT_EQ(forged.status().message().find('\n'), std::string::npos);
  EXPECT_LT(forged.status().message().size(), 300u);
  storage::SetKey key{1024, {1, 30, 30}, std::string(ConstructionOf(ConstructionKind::kNet).profile), 0};
  EXPECT_TRUE(storage::ValidateKey(key).ok());
}

TEST(Construction, TheLatticeProfileIsAValidKeyProfileOfItsOwn) {
  const std::string lattice(ConstructionOf(ConstructionKind::kLattice).profile);
  storage::SetKey key{1024, {1, 30, 30}, lattice, 0};
  EXPECT_TRUE(storage::ValidateKey(key).ok());
  const std::string optimized = storage::ProfileId(DefaultFrequencyParams(1024), OptimizerOptions{}, 1);
  EXPECT_NE(optimized, lattice);
  EXPECT_TRUE(ConstructionOfProfile(optimized).optimized());
}

class LatticeJobTest : public testing::SchedulerFixture {};

TEST_F(LatticeJobTest, ALatticeKeyIsComputedWithoutTheEngineAndStored) {
  // The engines wait at a closed gate: an optimization could not finish.
  gate_->Close();
  Scheduler::Options o;
  o.workers = 1;
  o.producer.optimizer.max_iterations = 20;
  StartWith(o);
  const CanonicalDirections dirs{1, 30, 30};
  const storage::SetKey lattice = scheduler_->producer().KeyFor(256, dirs, 2, ConstructionKind::kLattice);
  const storage::SetKey optimized = scheduler_->producer().KeyFor(256, dirs, 2);
  EXPECT_EQ(lattice.profile, "lattice-v2-w1");
  EXPECT_NE(optimized.profile, lattice.profile);
  EXPECT_EQ(scheduler_->producer().ProfileFor(256, ConstructionKind::kLattice), "lattice-v2-w1");

  auto ticket = MustAcquire(lattice, Priority::kInteractive);
  ASSERT_NE(ticket, nullptr);
  WaitDone(*ticket, 300);
  auto entry = ticket->Result();
  ASSERT_TRUE(entry.ok()) << entry.status().message();
  EXPECT_FALSE(ticket->from_cache());
  const storage::SetRecord& record = (*entry)->record();
  EXPECT_EQ(record.engine, "lattice");
  EXPECT_EQ(record.iterations, 0);
  EXPECT_EQ(record.loss.total, 0.0);
  EXPECT_GT(record.optimize_seconds, 0.0);
  auto choice = ChooseAlignedLatticeGenerator(256, {30.0});
  ASSERT_TRUE(choice.ok());
  // Realization 2 is seed 2 (the realization number itself).
  EXPECT_EQ(record.points, Rank1LatticePoints(256, choice->generator, 2));
  EXPECT_TRUE((*entry)->stored());
  EXPECT_TRUE(cache_->Contains(lattice).value());
  EXPECT_FALSE(cache_->Contains(optimized).value());
  EXPECT_EQ(metrics_.optimizations_started.load(), 1u);
  EXPECT_EQ(metrics_.optimizations_completed.load(), 1u);

  // The quarter-degree key is chosen for its exact angle.
  const CanonicalDirections quarter{1, 30, 30, 1};  // 30.25
  auto q = MustAcquire(scheduler_->producer().KeyFor(256, quarter, 0, ConstructionKind::kLattice),
                       Priority::kInteractive);
  ASSERT_NE(q, nullptr);
  WaitDone(*q, 300);
  auto qe = q->Result();
  ASSERT_TRUE(qe.ok()) << qe.status().message();
  auto qchoice = ChooseAlignedLatticeGenerator(256, {30.25});
  ASSERT_TRUE(qchoice.ok());
  EXPECT_EQ((*qe)->record().points, Rank1LatticePoints(256, qchoice->generator, 0));

  // The optimized key of the same directions is another job, held at the gate.
  auto opt = MustAcquire(optimized, Priority::kInteractive);
  ASSERT_NE(opt, nullptr);
  EXPECT_FALSE(opt->Done());
  gate_->Open();
  WaitDone(*opt, 600);
  auto oe = opt->Result();
  ASSERT_TRUE(oe.ok()) << oe.status().message();
  EXPECT_NE((*oe)->record().engine, "lattice");
  EXPECT_NE((*oe)->record().points, record.points);
}

// A tent-lattice key is the folded lattice the core chooses, under its own
// profile: never the plain lattice of the same directions, which shares the
// server's term cache (the terms are kept apart by the fold).
TEST_F(LatticeJobTest, ATentLatticeKeyIsTheFoldedLatticeUnderItsOwnProfile) {
  Scheduler::Options o;
  o.workers = 1;
  StartWith(o);
  const CanonicalDirections dirs{1, 30, 30};
  const storage::SetKey plain = scheduler_->producer().KeyFor(256, dirs, 3, ConstructionKind::kLattice);
  const storage::SetKey tent = scheduler_->producer().KeyFor(256, dirs, 3, ConstructionKind::kTentLattice);
  EXPECT_EQ(tent.profile, "tent-lattice-v1-w2");
  EXPECT_NE(tent.profile, plain.profile);
  EXPECT_EQ(ParseConstruction("tent-lattice").value()->kind, ConstructionKind::kTentLattice);
  std::vector<PointSet> got;
  for (const storage::SetKey& key : {plain, tent}) {
    auto ticket = MustAcquire(key, Priority::kInteractive);
    ASSERT_NE(ticket, nullptr);
    WaitDone(*ticket, 300);
    auto entry = ticket->Result();
    ASSERT_TRUE(entry.ok()) << entry.status().message();
    got.push_back((*entry)->record().points);
    EXPECT_EQ((*entry)->record().engine, ConstructionOfProfile(key.profile).name);
  }
  AlignedLatticeOptions folded;
  folded.folded = true;
  folded.window_deg = kTentLatticeWindowDeg;
  auto choice = ChooseAlignedLatticeGenerator(256, {30.0}, folded);
  ASSERT_TRUE(choice.ok());
  EXPECT_EQ(got[1], TentLatticePoints(256, choice->generator, 3));
  auto plain_choice = ChooseAlignedLatticeGenerator(256, {30.0});
  ASSERT_TRUE(plain_choice.ok());
  EXPECT_EQ(got[0], Rank1LatticePoints(256, plain_choice->generator, 3));
}

// Lattice keys share the search's terms (Scheduler::Options::
// lattice_terms_bytes): every key and realization, whatever came before it
// and however small the bound, is the lattice a fresh search chooses.
TEST_F(LatticeJobTest, KeysThatShareTheSearchesTermsGetTheLatticeAFreshSearchChooses) {
  Scheduler::Options o;
  o.workers = 2;
  o.producer.threads_per_worker = 1;
  o.producer.lattice_terms_bytes = 64 << 10;  // a few directions' terms: entries come and go
  StartWith(o);
  const std::vector<CanonicalDirections> keys = {{1, 30, 30}, {2, 10, 100}, {2, 30, 100}, {1, 10, 10},
                                                 {2, 12, 77},  {1, 30, 30, 1}};
  for (uint32_t realization : {0u, 5u}) {
    std::vector<std::unique_ptr<Ticket>> tickets;
    for (const CanonicalDirections& d : keys) {
      tickets.push_back(MustAcquire(scheduler_->producer().KeyFor(1024, d, realization, ConstructionKind::kLattice),
                                    Priority::kBatch));
      ASSERT_NE(tickets.back(), nullptr);
    }
    for (size_t k = 0; k < keys.size(); ++k) {
      WaitDone(*tickets[k], 600);
      auto entry = tickets[k]->Result();
      ASSERT_TRUE(entry.ok()) << entry.status().message();
      std::vector<double> dirs = {Phi1Degrees(keys[k])};
      if (keys[k].count == 2) dirs.push_back(Phi2Degrees(keys[k]));
      AlignedLatticeOptions fresh;
      fresh.window_deg = 1.0;
      auto choice = ChooseAlignedLatticeGenerator(1024, dirs, fresh);
      ASSERT_TRUE(choice.ok());
      EXPECT_EQ((*entry)->record().points, Rank1LatticePoints(1024, choice->generator, realization))
          << "key " << k << ", realization " << realization;
    }
  }
  EXPECT_EQ(metrics_.optimizations_completed.load(), 2 * keys.size());
}

}  // namespace
}  // namespace alignset::server
