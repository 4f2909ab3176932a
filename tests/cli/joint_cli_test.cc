// `alignset joint` (cli/cmd_joint.cc), run as a user runs it: what it
// writes is the sampler library's JointLattice, bit for bit.
#include <alignset/joint_lattice.h>
#include <alignset/npy.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli/cli_runner.h"

namespace alignset::cli {
namespace {

using test_support::CliRun;

CliRun Cli(const std::string& args) { return test_support::RunCli(args); }

TEST(JointCli, WritesThePixelsValuesAsTheLibraryMakesThem) {
  const std::string out = test_support::CliTempPath("joint.npy");
  const CliRun r = Cli("joint -n 256 -d 9 --fold 4:4 --seed 3 --pixel 17 --padded 2 --jitter -o " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  StatusOr<JointLattice> lattice = JointLattice::Create(256, 9, 3, {1, 1, 1, 1, 4}, {}, true);
  ASSERT_TRUE(lattice.ok());
  StatusOr<NpyArray> read = ReadNpy(out);
  ASSERT_TRUE(read.ok()) << read.status().message();
  ASSERT_EQ(read->shape, (std::vector<size_t>{256, 11}));
  for (uint32_t i = 0; i < 256; ++i) {
    for (uint32_t d = 0; d < 11; ++d) {
      ASSERT_EQ(read->values[i * 11 + d], lattice->Sample(17, i, d)) << "sample " << i << " dimension " << d;
    }
  }
  // The report names the library's generator and one spacing row a pair.
  std::string generator = "generator:";
  for (uint32_t z : lattice->generator()) generator.append(" ").append(std::to_string(z));
  EXPECT_NE(r.out.find(generator + "\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("d8   "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("d4 folded"), std::string::npos) << r.out;
  std::remove(out.c_str());
}

TEST(JointCli, SaysWhereASmallLatticeStopsAndPads) {
  StatusOr<JointLattice> lattice = JointLattice::Create(16, 9, 1);
  ASSERT_TRUE(lattice.ok());
  ASSERT_LT(lattice->dimensions(), 9u);
  const CliRun r = Cli("joint -n 16 -d 9");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(std::to_string(lattice->dimensions()) + " of the 9 dimensions asked in the lattice, "
                       "the rest padded"), std::string::npos) << r.out;
  // Every pair's spacing printed is the library's.
  const std::vector<uint32_t>& z = lattice->generator();
  char cell[16];
  std::snprintf(cell, sizeof(cell), "%.3f", JointLatticePairSpacing(16, z[0], z[1]));
  EXPECT_NE(r.out.find(std::string("d1     ") + cell), std::string::npos) << r.out;
}

TEST(JointCli, CsvHasAHeaderAndOneRowASample) {
  const std::string out = test_support::CliTempPath("joint.csv");
  ASSERT_EQ(Cli("joint -n 64 -d 3 -o " + out).exit_code, 0);
  std::ifstream in(out);
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_EQ(line, "d0,d1,d2");
  int rows = 0;
  while (std::getline(in, line)) ++rows;
  EXPECT_EQ(rows, 64);
  std::remove(out.c_str());
}

TEST(JointCli, DrawsThePixelsProjections) {
  const std::string png = test_support::CliTempPath("joint.png");
  std::remove(png.c_str());
  const CliRun r = Cli("joint -n 64 -d 4 --fold 3:4 --png " + png);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream f(png, std::ios::binary);
  char magic[4] = {};
  f.read(magic, 4);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG") << "no PNG at " << png << ": " << r.err;
  EXPECT_NE(r.out.find("2-D projections of the first 4 dimensions"), std::string::npos) << r.out;
  std::remove(png.c_str());
}

TEST(JointCli, BadInputIsOneLineAndNonZero) {
  const std::string out = test_support::CliTempPath("joint_bad.npy");
  for (const std::string& args : std::vector<std::string>{
           "joint -d 3", "joint -n 64", "joint -n 1 -d 3", "joint -n 64 -d 0", "joint -n 64 -d 17",
           "joint -n 64 -d 3 --fold 3:4", "joint -n 64 -d 3 --fold 2", "joint -n 64 -d 3 --fold 2:0",
           "joint -n 64 -d 3 --fold 2:4 --tent 2", "joint -n 64 -d 3 --tent 5", "joint -n 70000 -d 3",
           "joint -n 2 -d 3 --png " + test_support::CliTempPath("joint_bad.png")}) {
    const CliRun r = Cli(args + " -o " + out);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_EQ(test_support::CountLines(r.err), 1) << args << ": " << r.err;
    EXPECT_FALSE(std::ifstream(out).good()) << args << " wrote " << out;
  }
}

}  // namespace
}  // namespace alignset::cli
