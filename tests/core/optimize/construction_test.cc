// The constructions as values: every name, profile and version a stored set
// or a wire message carries, and each Build against the core call it stands
// for, so that a change to the table shows up as a changed cache key here.
#include "core/optimize/construction.h"

#include <gtest/gtest.h>

#include <set>

#include "core/optimize/aligned_lattice.h"
#include "core/optimize/aligned_net.h"

namespace alignset {
namespace {

TEST(ConstructionTable, NamesProfilesAndVersionsAreTheStoredOnes) {
  // These strings are cache keys and wire values: changing one strands every
  // stored set of that construction.
  struct Row {
    ConstructionKind kind;
    const char* name;
    const char* profile;
    int version;
    double window;
  };
  const Row rows[] = {{ConstructionKind::kOptimized, "optimized", "", 0, 0.0},
                      {ConstructionKind::kLattice, "lattice", "lattice-v2-w1", 2, 1.0},
                      {ConstructionKind::kTentLattice, "tent-lattice", "tent-lattice-v1-w2", 1, 2.0},
                      {ConstructionKind::kNet, "net", "net-v1-w1", 1, 1.0},
                      {ConstructionKind::kLatticeSequence, "lattice-sequence", "lattice-sequence-v1-w1", 1, 1.0}};
  ASSERT_EQ(Constructions().size(), std::size(rows));
  for (const Row& r : rows) {
    const Construction& c = ConstructionOf(r.kind);
    EXPECT_EQ(c.kind, r.kind);
    EXPECT_EQ(c.name, r.name);
    EXPECT_EQ(c.profile, r.profile);
    EXPECT_EQ(c.version, r.version);
    EXPECT_EQ(c.window_deg, r.window);
    EXPECT_EQ(FindConstruction(r.name), &c);
    if (!c.optimized()) {
      EXPECT_EQ(&ConstructionOfProfile(r.profile), &c);
    }
  }
  EXPECT_EQ(Constructions().front().kind, ConstructionKind::kOptimized);
  EXPECT_EQ(FindConstruction("")->kind, ConstructionKind::kOptimized);
  EXPECT_EQ(ConstructionOf(ConstructionKind::kTentLattice).window_deg, kTentLatticeWindowDeg);
  EXPECT_EQ(ConstructionOf(ConstructionKind::kLattice).window_deg, DefaultLatticeWindowDeg(false));
}

TEST(ConstructionTable, UnknownNamesAndProfilesAreNotConstructions) {
  for (const char* bad : {"Lattice", "sobol", " lattice", "optimised", "nets", "lattice-v2-w1"}) {
    EXPECT_EQ(FindConstruction(bad), nullptr) << bad;
  }
  // An optimizer profile (a hex id), or an old lattice version's, is no
  // construction's own: it is read as an optimized set's.
  for (const char* profile : {"0123456789abcdef", "lattice-v1-w1", "", "lattice"}) {
    EXPECT_TRUE(ConstructionOfProfile(profile).optimized()) << profile;
  }
  std::set<std::string_view> names, profiles;
  for (const Construction& c : Constructions()) {
    EXPECT_TRUE(names.insert(c.name).second) << c.name;
    EXPECT_TRUE(profiles.insert(c.profile).second) << c.profile;
  }
  EXPECT_EQ(KnownConstructionNames(),
            "'optimized' (the default, also ''), 'lattice', 'tent-lattice', 'net' and 'lattice-sequence'");
}

TEST(ConstructionTable, KindsAnswerWhatTheirCallersAsk) {
  EXPECT_TRUE(ConstructionOf(ConstructionKind::kOptimized).optimized());
  EXPECT_TRUE(ConstructionOf(ConstructionKind::kLattice).lattice());
  EXPECT_FALSE(ConstructionOf(ConstructionKind::kLattice).folded());
  EXPECT_TRUE(ConstructionOf(ConstructionKind::kTentLattice).lattice());
  EXPECT_TRUE(ConstructionOf(ConstructionKind::kTentLattice).folded());
  EXPECT_FALSE(ConstructionOf(ConstructionKind::kNet).lattice());
  EXPECT_FALSE(ConstructionOf(ConstructionKind::kNet).optimized());
  EXPECT_FALSE(ConstructionOf(ConstructionKind::kLatticeSequence).lattice());
  EXPECT_TRUE(ConstructionOf(ConstructionKind::kLatticeSequence).progressive());
  EXPECT_FALSE(ConstructionOf(ConstructionKind::kLattice).progressive());
}

TEST(ConstructionTable, ANetNeedsAPowerOfTwoTheOthersAnyN) {
  const Construction& net = ConstructionOf(ConstructionKind::kNet);
  EXPECT_TRUE(net.ValidateSize(16).ok());
  EXPECT_TRUE(net.ValidateSize(65536).ok());
  for (uint32_t n : {100u, 8u, 131072u, 0u}) {
    EXPECT_EQ(net.ValidateSize(n).code(), Status::Code::kInvalidArgument) << n;
  }
  EXPECT_EQ(net.ValidateSize(100).message(), "construction 'net' needs N a power of two from 16 to 65536, got 100");
  for (ConstructionKind k : {ConstructionKind::kOptimized, ConstructionKind::kLattice, ConstructionKind::kTentLattice}) {
    EXPECT_TRUE(ConstructionOf(k).ValidateSize(100).ok());
  }
}

TEST(ConstructionBuild, ALatticeIsTheChosenGeneratorsPointsForTheRealization) {
  for (ConstructionKind k : {ConstructionKind::kLattice, ConstructionKind::kTentLattice}) {
    const Construction& c = ConstructionOf(k);
    for (const std::vector<double>& dirs : {std::vector<double>{30.0}, std::vector<double>{12.0, 77.0}}) {
      auto built = c.Build(256, dirs, 3);
      ASSERT_TRUE(built.ok()) << built.status().message();
      AlignedLatticeOptions o;
      o.folded = c.folded();
      o.window_deg = c.window_deg;
      auto choice = ChooseAlignedLatticeGenerator(256, dirs, o);
      ASSERT_TRUE(choice.ok());
      EXPECT_EQ(built->lattice_generator, choice->generator);
      EXPECT_EQ(built->points, c.folded() ? TentLatticePoints(256, choice->generator, 3)
                                          : Rank1LatticePoints(256, choice->generator, 3));
      EXPECT_EQ(built->iterations, 0);
    }
  }
}

TEST(ConstructionBuild, ANetIsTheAlignedNetOfTheSeed) {
  const Construction& c = ConstructionOf(ConstructionKind::kNet);
  auto built = c.Build(64, {30.0}, 5);
  ASSERT_TRUE(built.ok()) << built.status().message();
  AlignedNetOptions o;
  o.window_deg = c.window_deg;
  auto net = AlignedNet(64, {30.0}, 5, o);
  ASSERT_TRUE(net.ok());
  EXPECT_EQ(built->points, net->points);
  EXPECT_EQ(built->iterations, net->sweeps);
  EXPECT_EQ(built->lattice_generator, 0u);
  // Bad input is the core's error, not a crash.
  auto bad = c.Build(100, {30.0}, 0);
  EXPECT_EQ(bad.status().code(), Status::Code::kInvalidArgument);
}

TEST(ConstructionBuild, TheOptimizedSetsAreNotBuilt) {
  auto built = ConstructionOf(ConstructionKind::kOptimized).Build(256, {30.0}, 0);
  EXPECT_EQ(built.status().code(), Status::Code::kFailedPrecondition);
}

}  // namespace
}  // namespace alignset
