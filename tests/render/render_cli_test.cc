// `alignset render` as a user runs it: the real binary, its files and exit
// statuses. (The aligned samplers against a real server: tests/e2e.)
#include <gtest/gtest.h>

#include <alignset/npy.h>

#include <cstdlib>
#include <algorithm>
#include <filesystem>
#include <string>

#include "render/pixel_samplers.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "tests/cli/cli_runner.h"

namespace alignset::render {
namespace {

using test_support::CliRun;
using test_support::RunCli;

// Standard output and error together, as a user sees them on a terminal.
std::string Said(const CliRun& r) { return r.out + r.err; }

class RenderCli : public ::testing::Test {
 protected:
  void SetUp() override {
    char tmpl[] = "/tmp/alignset-render-cli-XXXXXX";
    ASSERT_NE(mkdtemp(tmpl), nullptr);
    dir_ = tmpl;
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string dir_;
};

TEST_F(RenderCli, ReferenceIsTheExactImage) {
  const CliRun r = RunCli("render --scene shadow --size 24 --reference -o " + dir_ + "/ref.npy");
  ASSERT_EQ(r.exit_code, 0) << Said(r);
  auto img = ReadNpy(dir_ + "/ref.npy");
  ASSERT_TRUE(img.ok()) << img.status().message();
  EXPECT_EQ(img->shape, (std::vector<size_t>{24, 24}));
  EXPECT_EQ(img->values, MakeShadowScene(24, 24, 1).Reference());
}

TEST_F(RenderCli, ASamplersImageIsTheLibrarysRender) {
  const CliRun r = RunCli("render --scene antialias --size 32 --sampler owen-sobol -n 16 -s 3 -o " + dir_ + "/os.npy");
  ASSERT_EQ(r.exit_code, 0) << Said(r);
  EXPECT_NE(Said(r).find("MSE against the exact image"), std::string::npos) << Said(r);
  auto img = ReadNpy(dir_ + "/os.npy");
  ASSERT_TRUE(img.ok());
  const Scene scene = MakeAntialiasScene(32, 32, 3);
  auto sampler = MakePixelSampler({"owen-sobol", 16});
  ASSERT_TRUE(sampler.ok());
  EXPECT_EQ(img->values, Render(scene, **sampler, 3, 1));
  // Line samples across the estimated edge, and the screen-space sampler.
  EXPECT_EQ(RunCli("render --size 16 --sampler line --orientation random -n 8 -o " + dir_ + "/l.npy").exit_code, 0);
  EXPECT_EQ(RunCli("render --size 16 --sampler screen-space-rank1 -n 8 -o " + dir_ + "/s.npy").exit_code, 0);
}

TEST_F(RenderCli, TheSampleBudgetCountsThePrepass) {
  // A sampler that estimates the pixel's direction pays for its pre-pass
  // (the default, auto: edges on a quarter of N, here 16 at N = 64 and 256
  // at N = 2048, reused); one that does not reports N alone.
  CliRun r = RunCli("render --size 12 --sampler aligned-lattice -n 64 -o " + dir_ + "/l.npy");
  ASSERT_EQ(r.exit_code, 0) << Said(r);
  EXPECT_NE(Said(r).find("samples per pixel: 64 + 16 pre-pass (reused in the estimate) = 80\n"),
            std::string::npos)
      << Said(r);
  r = RunCli("render --size 4 --sampler pmj02bn-sheared -n 2048 -o " + dir_ + "/p.npy");
  ASSERT_EQ(r.exit_code, 0) << Said(r);
  EXPECT_NE(Said(r).find("samples per pixel: 2048 + 256 pre-pass (reused in the estimate) = 2304\n"),
            std::string::npos)
      << Said(r);
  r = RunCli("render --size 12 --sampler aligned-lattice -n 64 --prepass grid8 -o " + dir_ + "/l8.npy");
  ASSERT_EQ(r.exit_code, 0) << Said(r);
  EXPECT_NE(Said(r).find("samples per pixel: 64 + 64 pre-pass = 128\n"), std::string::npos) << Said(r);
  // Reused, the pre-pass is still counted, and said to be in the estimate;
  // a grid pre-pass cannot be reused (a one-line usage error).
  r = RunCli("render --size 12 --sampler aligned-lattice -n 64 --prepass samples64 --reuse-prepass on -o " +
             dir_ + "/lr.npy");
  ASSERT_EQ(r.exit_code, 0) << Said(r);
  EXPECT_NE(Said(r).find("samples per pixel: 64 + 64 pre-pass (reused in the estimate) = 128\n"),
            std::string::npos)
      << Said(r);
  r = RunCli("render --size 12 --sampler aligned-lattice -n 64 --prepass grid16 --reuse-prepass on -o " + dir_ +
             "/lg.npy");
  EXPECT_EQ(r.exit_code, 2) << Said(r);
  EXPECT_NE(Said(r).find("cannot be reused"), std::string::npos) << Said(r);
  const std::string refused = Said(r);
  EXPECT_EQ(std::count(refused.begin(), refused.end(), '\n'), 1) << refused;
  // The strictly unbiased weighting counts the same and refuses the same;
  // its image differs from the default's on the direction-less pixels.
  r = RunCli("render --size 12 --sampler aligned-lattice -n 64 --prepass samples64 --reuse-prepass unbiased -o " +
             dir_ + "/lu.npy");
  ASSERT_EQ(r.exit_code, 0) << Said(r);
  EXPECT_NE(Said(r).find("samples per pixel: 64 + 64 pre-pass (reused in the estimate) = 128\n"),
            std::string::npos)
      << Said(r);
  EXPECT_NE(ReadNpy(dir_ + "/lu.npy")->values, ReadNpy(dir_ + "/lr.npy")->values);
  r = RunCli("render --size 12 --sampler aligned-lattice -n 64 --prepass grid16 --reuse-prepass unbiased -o " +
             dir_ + "/lgu.npy");
  EXPECT_EQ(r.exit_code, 2) << Said(r);
  EXPECT_NE(Said(r).find("cannot be reused"), std::string::npos) << Said(r);
  r = RunCli("render --size 12 --sampler aligned-lattice-exact -n 64 -o " + dir_ + "/le.npy");
  ASSERT_EQ(r.exit_code, 0) << Said(r);
  EXPECT_NE(Said(r).find("samples per pixel: 64\n"), std::string::npos) << Said(r);
  r = RunCli("render --size 12 --sampler owen-sobol -n 64 -o " + dir_ + "/os.npy");
  ASSERT_EQ(r.exit_code, 0) << Said(r);
  EXPECT_NE(Said(r).find("samples per pixel: 64\n"), std::string::npos) << Said(r);
  EXPECT_EQ(Said(r).find("pre-pass"), std::string::npos) << Said(r);
  // Lattices of N - span ... N points: the budget reported is N, an upper bound.
  r = RunCli("render --size 12 --sampler aligned-lattice-exact -n 64 --lattice-size-span 6 -o " + dir_ + "/ls.npy");
  ASSERT_EQ(r.exit_code, 0) << Said(r);
  EXPECT_NE(Said(r).find("samples per pixel: 64\n"), std::string::npos) << Said(r);
  EXPECT_NE(Said(r).find("points a key on average"), std::string::npos) << Said(r);
}

TEST_F(RenderCli, TheAutomaticPrepassIsALatticeUpTo1024AndOnASharedDomain) {
  // The render's note names the pre-pass auto chose: a lattice (suffix l)
  // at N = 256 on both scenes; above 1024 on the shadow's shared light
  // square only (render/spectral_estimator.h, AutoPrepass).
  struct Case {
    const char* scene;
    int n;
    const char* prepass;
  };
  for (const Case& c : {Case{"antialias", 256, "nedges64s2l ("}, Case{"shadow", 256, "nedges64s2l ("},
                        Case{"antialias", 2048, "nedges256 ("}, Case{"shadow", 2048, "nedges256l ("}}) {
    const CliRun r = RunCli(std::string("render --scene ") + c.scene + " --size 4 --sampler aligned-lattice -n " +
                            std::to_string(c.n) + " -o " + dir_ + "/auto.npy");
    ASSERT_EQ(r.exit_code, 0) << Said(r);
    EXPECT_NE(Said(r).find(std::string("EstimateEdgeLines, ") + c.prepass), std::string::npos)
        << c.scene << " " << c.n << ": " << Said(r);
  }
}

TEST_F(RenderCli, BadInvocationsAreOneLineUsageErrors) {
  for (const std::string& args :
       {std::string("render --sampler no-such -n 16 -o x.npy"), std::string("render --sampler owen-sobol -o x.npy"),
        std::string("render --reference --sampler owen-sobol -o x.npy"),
        std::string("render --sampler owen-sobol -n 16 -o x.txt"), std::string("render --scene teapot --reference -o x.npy"),
        std::string("render --sampler jittered -n 15 -o x.npy"),
        std::string("render --sampler owen-sobol -n 64 --lattice-size-span 4 -o x.npy"),
        std::string("render --sampler aligned-lattice -n 20 --lattice-size-span 8 -o x.npy")}) {
    const CliRun r = RunCli(args + " --size 8");
    const std::string said = Said(r);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << said;
    EXPECT_EQ(std::count(said.begin(), said.end(), '\n'), 1) << args << ": " << said;
  }
  // A server that is not there is a failure, not a usage error.
  const CliRun r = RunCli("render --size 8 --sampler aligned -n 16 --server 127.0.0.1:1 --timeout 5 -o " + dir_ + "/a.npy");
  EXPECT_EQ(r.exit_code, 1) << Said(r);
  EXPECT_NE(Said(r).find("UNAVAILABLE"), std::string::npos) << Said(r);
}

}  // namespace
}  // namespace alignset::render
