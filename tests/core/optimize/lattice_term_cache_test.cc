// The aligned-lattice search's term cache: what it keeps, what it gives
// back, and that it stays within its bound, dropping heavy objects before
// terms (tests/core/optimize/aligned_lattice_test.cc checks the choices).
#include "core/optimize/lattice_term_cache.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

namespace alignset {
namespace {

using Key = LatticeTermCache::Key;
using Stage = LatticeTermCache::Stage;
using Terms = std::vector<LatticeTermCache::Terms>;

std::shared_ptr<const Terms> Dense(Terms t) { return std::make_shared<const Terms>(std::move(t)); }

Key Coarse(double direction) { return Key{1024, Stage::kCoarse, 1.0, direction}; }

TEST(LatticeTermCache, GivesBackWhatWasPut) {
  LatticeTermCache cache;
  EXPECT_EQ(cache.FindDense(Coarse(30)), nullptr);
  cache.PutDense(Coarse(30), Dense({{1.0, 0.5}, {2.0, 0.5}, {3.0, 0.25}}));
  auto held = cache.FindDense(Coarse(30));
  ASSERT_NE(held, nullptr);
  ASSERT_EQ(held->size(), 3u);
  EXPECT_EQ((*held)[2].edges, 3.0);
  EXPECT_EQ((*held)[2].corner, 0.25);
  // Other N, window or direction: another entry.
  EXPECT_EQ(cache.FindDense(Key{4096, Stage::kCoarse, 1.0, 30}), nullptr);
  EXPECT_EQ(cache.FindDense(Key{1024, Stage::kCoarse, 0.5, 30}), nullptr);
  EXPECT_EQ(cache.FindDense(Coarse(30.25)), nullptr);

  const Key full{1024, Stage::kFull, 1.0, 30};
  cache.PutSparse(full, {5, 7}, {{-1.5, -9.0}, {-2.5, -8.0}});
  cache.PutSparse(full, {9}, {{-3.5, -7.0}});
  std::vector<LatticeTermCache::Terms> values;
  std::vector<bool> found;
  cache.FindSparse(full, {7, 8, 9, 5}, &values, &found);
  EXPECT_EQ(found, (std::vector<bool>{true, false, true, true}));
  EXPECT_EQ(values[0].edges, -2.5);
  EXPECT_EQ(values[0].corner, -8.0);
  EXPECT_EQ(values[2].edges, -3.5);
  EXPECT_EQ(values[3].edges, -1.5);
  const LatticeTermCache::Stats s = cache.stats();
  EXPECT_EQ(s.hits, 3u + 3u);  // three dense terms, three sparse ones
  EXPECT_EQ(s.entries, 2u);
}

TEST(LatticeTermCache, EvictsTheLeastRecentlyUsedWithinItsBound) {
  const auto terms = Dense(Terms(500));  // about 8 kB an entry
  LatticeTermCache cache(30000);
  cache.PutDense(Coarse(1), terms);
  cache.PutDense(Coarse(2), terms);
  cache.PutDense(Coarse(3), terms);
  ASSERT_NE(cache.FindDense(Coarse(1)), nullptr);  // 1 is now the newest
  cache.PutDense(Coarse(4), terms);                // 2 goes
  EXPECT_LE(cache.stats().bytes, 30000u);
  EXPECT_NE(cache.FindDense(Coarse(1)), nullptr);
  EXPECT_EQ(cache.FindDense(Coarse(2)), nullptr);
  EXPECT_NE(cache.FindDense(Coarse(3)), nullptr);
  EXPECT_NE(cache.FindDense(Coarse(4)), nullptr);
  // Larger than the whole bound: not kept, nothing else lost.
  cache.PutDense(Coarse(5), Dense(Terms(5000)));
  EXPECT_EQ(cache.FindDense(Coarse(5)), nullptr);
  EXPECT_EQ(cache.stats().entries, 3u);
}

TEST(LatticeTermCache, DropsObjectsBeforeTerms) {
  LatticeTermCache cache(40000);
  const Key family{1024, Stage::kFullFamily, 1.0, 30};
  cache.PutObject(family, std::make_shared<const int>(7), 20000);
  cache.PutDense(Coarse(1), Dense(Terms(500)));  // older than the next object
  ASSERT_NE(cache.FindObject(family), nullptr);                // the object is the newest
  cache.PutDense(Coarse(2), Dense(Terms(750)));
  // Over the bound: the object goes although a term entry is older.
  EXPECT_EQ(cache.FindObject(family), nullptr);
  EXPECT_NE(cache.FindDense(Coarse(1)), nullptr);
  EXPECT_NE(cache.FindDense(Coarse(2)), nullptr);
  EXPECT_LE(cache.stats().bytes, 40000u);
}

}  // namespace
}  // namespace alignset
