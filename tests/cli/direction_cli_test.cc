// `alignset direction` through the real binary (issue 12): the documented
// grid layout (values[j, i] = f((i + 1/2) / W, (j + 1/2) / H), rows along y),
// text samples, --two and --json, "no dominant direction" as a status, and a
// one-line usage error for every bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "core/analysis/patch_sampling.h"
#include "core/analysis/step_integrand.h"
#include "tests/cli/cli_runner.h"
#include "tests/client/npy_test_file.h"

namespace alignset::cli {
namespace {

using test_support::CliRun;
using test_support::CountLines;
using test_support::RunCli;
using test_support::WriteNpy;

std::string TempPath(const std::string& name) { return test_support::CliTempPath(name); }

// The patch's values in C order of an (H, W) array: row j (y), column i (x).
void WriteGrid(const std::string& path, const GridPatch& g) {
  WriteNpy(path, {static_cast<size_t>(g.height), static_cast<size_t>(g.width)}, g.values);
}

double AngleError(double a, double b) {
  const double d = std::fmod(std::fabs(a - b), 180.0);
  return std::min(d, 180.0 - d);
}

// The number after "key " on its own line, NaN when there is none.
double Field(const std::string& out, const std::string& key) {
  const size_t at = out.find(key + " ");
  if (at == std::string::npos || (at > 0 && out[at - 1] != '\n')) return NAN;
  return std::atof(out.c_str() + at + key.size() + 1);
}

Integrand2 Step(double theta, double offset) {
  const StepIntegrand f(theta, offset);
  return [f](const Point2& p) { return f(p); };
}

TEST(DirectionCli, GridRowsAlongYAndATransposedArrayReadsNinetyMinusTheta) {
  // A non-square 64 x 48 grid, so rows and columns cannot be mixed up silently.
  const double theta = 23.0;
  const GridPatch g = PointSampledGrid(Step(theta, 0.05), 64, 48);
  const std::string path = TempPath("step.npy");
  WriteGrid(path, g);
  const CliRun r = RunCli("direction " + path);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(CountLines(r.out), 3) << r.out;
  EXPECT_LT(AngleError(Field(r.out, "theta"), theta), 1.0) << r.out;
  EXPECT_GT(Field(r.out, "kappa"), 1.0) << r.out;
  const double confidence = Field(r.out, "confidence");
  EXPECT_GT(confidence, 0.0);
  EXPECT_LE(confidence, 1.0);

  // The same values written transposed, shape (W, H): x and y swap, so the
  // reading is the mirror image about the diagonal, 90 - theta.
  std::vector<double> t(g.values.size());
  for (int j = 0; j < g.height; ++j)
    for (int i = 0; i < g.width; ++i) t[static_cast<size_t>(i) * g.height + j] = g.values[j * g.width + i];
  const std::string tpath = TempPath("step_t.npy");
  WriteNpy(tpath, {static_cast<size_t>(g.width), static_cast<size_t>(g.height)}, t);
  const CliRun rt = RunCli("direction " + tpath);
  ASSERT_EQ(rt.exit_code, 0) << rt.err;
  EXPECT_LT(AngleError(Field(rt.out, "theta"), 90.0 - theta), 1.0) << rt.out;

  // The transposed buffer declared Fortran-order is the original array again.
  const std::string fpath = TempPath("step_f.npy");
  WriteNpy(fpath, {static_cast<size_t>(g.height), static_cast<size_t>(g.width)}, t, true);
  const CliRun rf = RunCli("direction " + fpath);
  ASSERT_EQ(rf.exit_code, 0) << rf.err;
  EXPECT_EQ(rf.out, r.out);
}

TEST(DirectionCli, TextSamplesJsonAndTwoDirections) {
  const double theta = 131.0;
  const SampledPatch s = RandomSamples(Step(theta, -0.1), 4096, 5);
  const std::string path = TempPath("samples.txt");
  {
    std::ofstream out(path);
    out << "# x y f\n\n";
    out.precision(17);
    for (size_t j = 0; j < s.points.size(); ++j) {
      out << s.points[j].x << ' ' << s.points[j].y << ' ' << s.values[j] << '\n';
    }
  }
  const CliRun r = RunCli("direction " + path);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_LT(AngleError(Field(r.out, "theta"), theta), 3.0) << r.out;
  // The same samples from stdin.
  const CliRun in = RunCli("direction - < " + path);
  EXPECT_EQ(in.out, r.out);

  // Two crossing edges of contrast 1 : 0.5: theta first, theta2 second.
  const double t1 = 40.0, t2 = 115.0;
  const StepIntegrand e1(t1, 0.03), e2(t2, -0.07);
  const GridPatch g =
      PointSampledGrid([&](const Point2& p) { return e1(p) + 0.5 * e2(p); }, 64, 64);
  const std::string gpath = TempPath("cross.npy");
  WriteGrid(gpath, g);
  const CliRun two = RunCli("direction --two " + gpath);
  ASSERT_EQ(two.exit_code, 0) << two.err;
  EXPECT_EQ(CountLines(two.out), 4) << two.out;
  EXPECT_LT(AngleError(Field(two.out, "theta"), t1), 1.0) << two.out;
  EXPECT_LT(AngleError(Field(two.out, "theta2"), t2), 1.0) << two.out;

  const CliRun json = RunCli("direction --two --json " + gpath);
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_EQ(CountLines(json.out), 1);
  // The same numbers as the text form, as one object.
  char expect[256];
  std::snprintf(expect, sizeof(expect), "{\"theta\": %.4f, ", Field(two.out, "theta"));
  EXPECT_EQ(json.out.rfind(expect, 0), 0u) << json.out << " vs " << expect;
  EXPECT_NE(json.out.find("\"kappa\": "), std::string::npos);
  EXPECT_NE(json.out.find("\"confidence\": "), std::string::npos);
  std::snprintf(expect, sizeof(expect), "\"theta2\": %.4f}", Field(two.out, "theta2"));
  EXPECT_NE(json.out.find(expect), std::string::npos) << json.out;
}

TEST(DirectionCli, NoDominantDirectionIsAStatusNotAnAngle) {
  GridPatch constant{32, 32, std::vector<double>(32 * 32, 0.7)};
  const GridPatch disk = PointSampledGrid(
      [](const Point2& p) { return std::hypot(p.x - 0.5, p.y - 0.45) < 0.3 ? 1.0 : 0.0; }, 64, 64);
  for (const auto& [name, g] : {std::pair{"constant", constant}, std::pair{"disk", disk}}) {
    const std::string path = TempPath(std::string(name) + ".npy");
    WriteGrid(path, g);
    const CliRun r = RunCli("direction " + path);
    EXPECT_EQ(r.exit_code, 1) << name << ": " << r.out << r.err;
    EXPECT_EQ(r.out.rfind("theta none\nreason ", 0), 0u) << name << ": " << r.out;
    const CliRun j = RunCli("direction --json " + path);
    EXPECT_EQ(j.exit_code, 1);
    EXPECT_EQ(j.out.rfind("{\"theta\": null, \"reason\": \"", 0), 0u) << j.out;
  }
}

TEST(DirectionCli, BadInputIsOneUsageLine) {
  const GridPatch good = PointSampledGrid(Step(10.0, 0.0), 16, 16);
  std::vector<std::pair<std::string, std::string>> cases;  // file, expected words
  {
    const std::string p = TempPath("nan.npy");
    GridPatch g = good;
    g.values[37] = NAN;
    WriteGrid(p, g);
    cases.push_back({p, "not finite"});
  }
  {
    const std::string p = TempPath("small.npy");
    WriteNpy(p, {4, 4}, std::vector<double>(16, 1.0));
    cases.push_back({p, "at least 8 x 8"});
  }
  {
    const std::string p = TempPath("wide.npy");  // one side past the limit
    WriteNpy(p, {8, static_cast<size_t>(kMaxPatchSide) + 1},
             std::vector<double>(8 * (kMaxPatchSide + 1), 1.0));
    cases.push_back({p, std::to_string(kMaxPatchSide)});
  }
  {
    const std::string p = TempPath("cells.npy");  // the header alone claims too many cells
    WriteNpy(p, {4096, 4096}, {});
    cases.push_back({p, "cells"});
  }
  {
    const std::string p = TempPath("short.npy");  // body shorter than its shape
    WriteNpy(p, {16, 16}, std::vector<double>(100, 1.0));
    cases.push_back({p, "body holds"});
  }
  {
    const std::string p = TempPath("flat.npy");
    WriteNpy(p, {64}, std::vector<double>(64, 1.0));
    cases.push_back({p, "not a grid"});
  }
  {
    const std::string p = TempPath("empty.txt");
    std::ofstream(p) << "# nothing\n";
    cases.push_back({p, "no samples"});
  }
  {
    const std::string p = TempPath("two_fields.txt");
    std::ofstream(p) << "0.1 0.2 1\n0.3 0.4\n";
    cases.push_back({p, ":2: expected three numbers"});
  }
  {
    const std::string p = TempPath("nan.txt");
    std::ofstream(p) << "0.1 0.2 1\n0.3 0.4 nan\n";
    cases.push_back({p, "not finite"});
  }
  {
    const std::string p = TempPath("outside.txt");
    std::ofstream(p) << "0.1 0.2 1\n1.5 0.4 0\n";
    cases.push_back({p, "sample 1"});
  }
  cases.push_back({TempPath("missing.npy"), "cannot read"});
  for (const auto& [path, words] : cases) {
    const CliRun r = RunCli("direction " + path);
    EXPECT_EQ(r.exit_code, 2) << path << ": " << r.out << r.err;
    EXPECT_EQ(r.out, "") << path;
    EXPECT_EQ(CountLines(r.err), 1) << path << ": " << r.err;
    EXPECT_EQ(r.err.rfind("alignset direction: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << path << ": " << r.err;
  }
}

}  // namespace
}  // namespace alignset::cli
