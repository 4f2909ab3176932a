// The command line as a user meets it: the real binary, real files.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "cli/point_file.h"
#include "tests/cli/cli_runner.h"

namespace {

using alignset::test_support::CliRun;
using alignset::test_support::RunCli;

std::string TempPath(const std::string& name) {
  return alignset::test_support::CliTempPath(name);
}

int Lines(const std::string& s) { return alignset::test_support::CountLines(s); }

TEST(Cli, BadInputGetsOneLineErrorAndNonZeroExit) {
  const std::string out = TempPath("bad.txt");
  const char* cases[] = {
      "optimize --n 8 --dir 30 --out ",
      "optimize --n abc --dir 30 --out ",
      "optimize --n 64 --dir thirty --out ",
      "optimize --n 64 --dir nan --out ",
      "optimize --n 64 --dir inf --out ",
      "optimize --n 64 --dir 1 --dir 2 --dir 3 --dir 4 --dir 5 --dir 6 --dir 7 --dir 8 --dir 9 --out ",
      "optimize --n 64 --out ",
      "optimize --n 64 --dir 30 --engine warp --out ",
      "optimize --n 64 --dir 30 --bogus 1 --out ",
      "optimize --n 15 --dir 30 --construction lattice --out ",
      "optimize --n 64 --dir nan --construction lattice --out ",
      "optimize --n 64 --dir 30 --construction lattice --window 11 --out ",
      "optimize --n 64 --dir 30 --construction mesh --out ",
      "evaluate --normal 30 /nonexistent/file.txt --x ",
  };
  for (const char* c : cases) {
    const CliRun r = RunCli(std::string(c) + out);
    EXPECT_NE(r.exit_code, 0) << c;
    EXPECT_EQ(Lines(r.err), 1) << c << " printed: " << r.err;
    EXPECT_EQ(r.out, "") << c;
    EXPECT_NE(r.err.find("alignset"), std::string::npos) << r.err;
  }
  const CliRun unwritable = RunCli("optimize --n 64 --dir 30 --out /nonexistent-dir/set.txt");
  EXPECT_NE(unwritable.exit_code, 0);
  EXPECT_EQ(Lines(unwritable.err), 1) << unwritable.err;
  EXPECT_EQ(unwritable.out, "");
  EXPECT_NE(unwritable.err.find("cannot write"), std::string::npos);
  EXPECT_NE(RunCli("frobnicate").exit_code, 0);
}

TEST(Cli, OptimizeWritesTheSetAndEvaluateReadsIt) {
  const std::string out = TempPath("set.txt");
  const CliRun r = RunCli("optimize --n 64 --dir 30 --max-iterations 50 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("spectrum loss"), std::string::npos);
  auto pts = alignset::cli::ReadPointFile(out);
  ASSERT_TRUE(pts.ok()) << pts.status().ToString();
  EXPECT_EQ(pts->size(), 64u);
  const CliRun e = RunCli("evaluate " + out + " --normal 30 --shifts 1024");
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_NE(e.out.find("variance ratio"), std::string::npos);
  EXPECT_NE(e.out.find("mean periodogram 30 deg"), std::string::npos);
}

TEST(Cli, OptimizeLatticeWritesACentredLatticeAndItsRealizations) {
  const std::string out = TempPath("lattice.txt");
  const CliRun r = RunCli("optimize --n 256 --dir 37 --construction lattice -m 2 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("aligned rank-1 lattice, generator"), std::string::npos) << r.out;
  auto sets = alignset::cli::ReadPointSets(out);
  ASSERT_TRUE(sets.ok()) << sets.status().ToString();
  ASSERT_EQ(sets->size(), 2u);
  EXPECT_NE((*sets)[0], (*sets)[1]);
  for (const alignset::PointSet& set : *sets) {
    ASSERT_EQ(set.size(), 256u);
    for (const alignset::Point2& p : set) {  // cell centres (i + 1/2) / N
      EXPECT_DOUBLE_EQ(p.x * 256 - 0.5, std::round(p.x * 256 - 0.5));
      EXPECT_DOUBLE_EQ(p.y * 256 - 0.5, std::round(p.y * 256 - 0.5));
    }
  }
}

TEST(PointFile, TextAndNpyRoundTripBitExact) {
  alignset::PointSet pts = {{0.1, 0.2}, {0.999999999999, 1e-300}, {0.5, 0.25}};
  for (const char* ext : {".txt", ".npy"}) {
    const std::string path = TempPath(std::string("rt") + ext);
    ASSERT_TRUE(alignset::cli::WritePointFile(path, pts, "comment line").ok());
    auto back = alignset::cli::ReadPointFile(path);
    ASSERT_TRUE(back.ok()) << back.status().ToString();
    EXPECT_EQ(*back, pts) << ext;
  }
}

TEST(PointFile, MalformedTextIsRejectedWithItsLine) {
  const std::string path = TempPath("malformed.txt");
  std::ofstream(path) << "# header\n0.1 0.2\n0.3 oops\n";
  auto r = alignset::cli::ReadPointFile(path);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find(":3:"), std::string::npos) << r.status().message();
}

}  // namespace
