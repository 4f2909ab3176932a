// alignset analyze / convergence and optimize with any number of directions
// (issue 14), through the real binary: bad input gets one line and status 2,
// and the outputs say what they should.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "cli/point_file.h"
#include "core/sampling/samplers.h"
#include "tests/cli/cli_runner.h"

namespace alignset::cli {
namespace {

using test_support::CliRun;
using test_support::RunCli;

std::string TempPath(const std::string& name) { return test_support::CliTempPath(name); }

std::string SampleFile(const std::string& name, const std::string& sampler, uint32_t n,
                       uint64_t seed) {
  const std::string path = TempPath(name);
  auto points = Sample(sampler, n, seed);
  EXPECT_TRUE(points.ok());
  EXPECT_TRUE(WritePointFile(path, *points).ok());
  return path;
}

TEST(AnalysisCli, BadInputGetsOneLineAndStatusTwo) {
  const std::string out = TempPath("bad_out.txt");
  const std::string not_points = TempPath("not_points.txt");
  {
    std::ofstream f(not_points);
    f << "this is not a point set\n";
  }
  const std::string a64 = SampleFile("a64.txt", "random", 64, 1);
  const std::string b128 = SampleFile("b128.txt", "random", 128, 1);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"optimize -n 64 --dir 1 --dir 2 --dir 3 --dir 4 --dir 5 --dir 6 --dir 7 --dir 8 --dir 9 -o " +
           out,
       "alignset optimize: give 1 to 8 --dir angles"},
      {"optimize -n 64 --dir 30 --dir 50 --dir 210 -o " + out,
       "alignset optimize: --dir 210 repeats --dir 30"},
      {"optimize -n 64 --dir 30 --dir 50 --dir 90 -o " + out,
       "alignset optimize: duplicate direction 90 (0 and 90 are always included)"},
      {"optimize -n 64 --dir 30 --revert-on sometimes -o " + out,
       "alignset optimize: --revert-on must be spectrum or total"},
      {"analyze " + not_points, "alignset analyze: " + not_points + ":1:"},
      {"analyze /nonexistent.txt", "alignset analyze: cannot read"},
      {"analyze " + a64 + " " + b128, "alignset analyze: the sets have different N"},
      {"analyze", "alignset analyze: SET is required"},
      {"convergence --integrand step:30", "alignset convergence: name at least one --sampler"},
      {"convergence --sampler nope --integrand step:30", "alignset convergence: unknown sampler"},
      {"convergence --sampler random --integrand wobble", "alignset convergence: unknown integrand"},
      {"convergence --sampler random --integrand edges:0:90:270",
       "alignset convergence: integrand 'edges:0:90:270'"},
      {"convergence --set x=" + not_points + " --integrand disk",
       "alignset convergence: --set 'x="},
      {"convergence --set x=" + TempPath("n{n}.txt") + " --integrand disk -n 64",
       "alignset convergence: cannot read"},
      {"convergence --sampler random --integrand disk --homogenize sometimes",
       "alignset convergence: --homogenize must be"},
  };
  for (const auto& [args, message] : cases) {
    const CliRun r = RunCli(args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_EQ(test_support::CountLines(r.err), 1) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind(message, 0), 0u) << args << ": " << r.err;
  }
}

TEST(AnalysisCli, OptimizeTakesUpToEightDirectionsAndSharesTheBudget) {
  const std::string out = TempPath("k5.txt");
  const CliRun r = RunCli("optimize -n 64 --dir 20 --dir 50 --dir 110 --dir 140 --dir 160 "
                          "--max-iterations 30 --engine direct --threads 1 -o " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("directions     0, 90, 20"), std::string::npos) << r.out;
  auto points = ReadPointFile(out);
  ASSERT_TRUE(points.ok());
  EXPECT_EQ(points->size(), 64u);
}

TEST(AnalysisCli, AnalyzeJsonHasTheProfilesOfTheMeanOfTheSets) {
  const std::string sets = TempPath("four.npy");
  std::vector<PointSet> four;
  for (uint64_t s = 1; s <= 4; ++s) four.push_back(*Sample("owen-sobol", 256, s));
  ASSERT_TRUE(WritePointSets(sets, four).ok());
  const CliRun r = RunCli("analyze " + sets + " --dir 30 --max-freq 16 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* key : {"\"kind\":\"spectrum\"", "\"sets\":4", "\"n\":256", "\"radial\":",
                          "\"directional\":[{\"deg\":0,", "{\"deg\":30,", "\"angular\":",
                          "\"power\":[["}) {
    EXPECT_NE(r.out.find(key), std::string::npos) << key << " in " << r.out.substr(0, 300);
  }
}

TEST(AnalysisCli, ConvergenceFitsSlopesAndDrawsThePlot) {
  const std::string png = TempPath("conv.png");
  std::remove(png.c_str());
  const CliRun r = RunCli("convergence --sampler random --sampler jittered --integrand disk "
                          "-n 64,256,1024 -m 8 --shifts 64 --png " + png);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // One line per sampler with its slope: random about -1, jittered about -1.5.
  for (const char* name : {"random\tdisk r=0.3\t8\t", "jittered\tdisk r=0.3\t8\t"}) {
    const size_t at = r.out.find(name);
    ASSERT_NE(at, std::string::npos) << r.out;
    const std::string line = r.out.substr(at, r.out.find('\n', at) - at);
    const double slope = std::stod(line.substr(line.rfind('\t') + 1));
    if (line.rfind("random", 0) == 0) {
      EXPECT_NEAR(slope, -1.0, 0.3) << line;
    } else {
      EXPECT_NEAR(slope, -1.5, 0.3) << line;
    }
  }
  std::ifstream f(png, std::ios::binary);
  char magic[4] = {};
  f.read(magic, 4);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG") << "no PNG at " << png << ": " << r.err;
}

}  // namespace
}  // namespace alignset::cli
