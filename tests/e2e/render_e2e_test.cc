// The renderer's aligned samplers end to end: sets fetched from the real
// alignset-server on loopback through the client library, then a few pixels
// of both scenes rendered with them and checked against the exact reference.
#include <gtest/gtest.h>

#include <cmath>

#include "render/direction.h"
#include "render/lattice_sets.h"
#include "render/pixel_samplers.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "render/set_fetch.h"
#include "render/spectral_estimator.h"
#include "core/optimize/aligned_lattice.h"
#include "core/util/hash.h"
#include <alignset/client.h>
#include <alignset/npy.h>
#include "tests/e2e/server_process.h"

namespace alignset::render {
namespace {

using e2e::ServerProcess;
using e2e::TempDir;

TEST(RenderE2e, AlignedSamplersFromARealServerAreUnbiasedOnBothScenes) {
  TempDir dir;
  ServerProcess server(dir.path(), {"--max-iterations", "200", "--workers", "2",
                                    "--threads-per-worker", "1"});
  ASSERT_EQ(server.error(), "");
  ConnectOptions o;
  o.address = server.address();
  auto client = ServiceClient::Connect(o);
  ASSERT_TRUE(client.ok()) << client.status().message();

  constexpr uint32_t kN = 16;
  for (const char* name : {"antialias", "shadow"}) {
    const Scene scene = *MakeScene(name, 128, 128, 1);
    const std::vector<PixelDirection> exact = GeometryDirections(scene);
    // A few edge pixels of each kind and a smooth one, spread over the image.
    const std::vector<PixelClass> classes = scene.Classes();
    std::vector<size_t> pixels;
    int one = 0, two = 0, smooth = 0;
    for (size_t k = 0; k < classes.size(); ++k) {
      const size_t i = (k * 7919 + 101) % classes.size();
      const bool edge = classes[i] == PixelClass::kEdge;
      if (edge && exact[i].kind == PixelDirection::Kind::kOne && one < 3) pixels.push_back(i), ++one;
      if (edge && exact[i].kind == PixelDirection::Kind::kTwo && two < 2) pixels.push_back(i), ++two;
      if (classes[i] == PixelClass::kSmooth && smooth < 1) pixels.push_back(i), ++smooth;
    }
    ASSERT_EQ(pixels.size(), 6u) << name;
    // The estimator of record on these pixels, seeded as EstimateDirections
    // does (each pixel's own fit: the pooling with its neighbours is tested
    // in tests/render).
    const auto estimator = MakeSpectralEstimator(*ParsePrepass(kDefaultPrepass));
    std::vector<PixelDirection> estimated(scene.size());
    for (size_t i : pixels) estimated[i] = estimator->Estimate(scene.Pixel(i), HashCombine(1, i));
    // Only the pairs these pixels need: the test stays seconds long.
    AlignedPolicy policy;
    std::vector<PixelDirection> mine_exact(exact.size()), mine_est(estimated.size());
    for (size_t i : pixels) {
      mine_exact[i] = exact[i];
      mine_est[i] = estimated[i];
    }
    std::set<std::pair<int, int>> pairs = NeededPairs(mine_exact, policy);
    for (const auto& p : NeededPairs(mine_est, policy)) pairs.insert(p);
    ASSERT_FALSE(pairs.empty()) << name;  // the two-direction pixels need them
    double fetched = 0.0, fetch_total = 0.0;
    auto table = FetchAlignedSets(**client, kN, pairs,
                                  [&](const std::string& stage, double done, double total, const std::string&) {
                                    if (stage.rfind("fetch", 0) == 0) fetched = done, fetch_total = total;
                                  });
    ASSERT_TRUE(table.ok()) << table.status().message();
    // The 46 one-direction keys and the pairs' canonical keys, each once.
    EXPECT_EQ(fetch_total, 46.0 + PairKeys(pairs).size());  // progress reached the end
    EXPECT_EQ(fetched, fetch_total);
    ASSERT_NE(table->table, nullptr);
    EXPECT_EQ(table->construction, "optimized");
    const SetTable::Sections sections = table->table->Resolve(kN, table->construction);
    // The table aligns each set as the server does: bit for bit what the
    // server serves for that direction or pair.
    for (int deg : {0, 17, 45, 46, 90, 123, 179}) {
      auto direct = (*client)->GetAlignedSet(kN, {static_cast<double>(deg)});
      ASSERT_TRUE(direct.ok());
      auto mine = table->table->Find(sections, {SetChoice::Kind::kOne, deg, 0});
      ASSERT_TRUE(mine.ok()) << mine.status().message();
      EXPECT_EQ(*mine->points, direct->points) << deg << " deg";
    }
    for (const auto& [a, b] : pairs) {
      auto direct = (*client)->GetAlignedSet(kN, {static_cast<double>(a), static_cast<double>(b)});
      ASSERT_TRUE(direct.ok());
      auto mine = table->table->Find(sections, {SetChoice::Kind::kTwo, a, b});
      ASSERT_TRUE(mine.ok()) << a << "," << b << ": " << mine.status().message();
      EXPECT_EQ(*mine->points, direct->points) << a << "," << b;
    }

    for (const char* sampler : {"aligned", "aligned-exact"}) {
      for (AlignedPolicy::None none : {AlignedPolicy::None::kOwenSobol, AlignedPolicy::None::kAxisSet}) {
        SamplerConfig c{sampler, kN};
        c.estimated = &mine_est;
        c.exact = &mine_exact;
        c.sets = &*table;
        c.policy.none = none;
        auto s = MakePixelSampler(c);
        ASSERT_TRUE(s.ok()) << s.status().message();
        for (size_t i : pixels) {
          constexpr int kReps = 24;
          std::vector<double> e;
          for (int r = 1; r <= kReps; ++r) {
            e.push_back(RenderPixel(scene, **s, int(i % 128), int(i / 128), r));
          }
          double mean = 0.0, ss = 0.0;
          for (double v : e) mean += v / kReps;
          for (double v : e) ss += (v - mean) * (v - mean);
          const double sd = std::sqrt(ss / (kReps - 1));
          ASSERT_TRUE(std::isfinite(mean)) << sampler << " pixel " << i;
          EXPECT_NEAR(mean, scene.Pixel(i).Exact(), 5.0 * sd / std::sqrt(double(kReps)) + 1e-12)
              << name << " " << sampler << " pixel " << i;
          if (classes[i] == PixelClass::kEdge) {
            EXPECT_GT(sd, 0.0) << name << " " << sampler;
          }
        }
      }
    }
  }
}

TEST(RenderE2e, TheCommandLineExportsTheSpaceAndRendersWithAlignedSets) {
  TempDir dir;
  ServerProcess server(dir.path(), {"--max-iterations", "200", "--workers", "2",
                                    "--threads-per-worker", "1"});
  ASSERT_EQ(server.error(), "");
  const std::string cli = std::string(ALIGNSET_CLI_PATH) + " ";
  // The whole one-direction space of N as one (46, N, 2) array: set k is the
  // canonical set phi = k, i.e. what the server serves for k degrees.
  const std::string space = dir.path() + "/space.npy";
  auto r = e2e::RunCommand(cli + "get --space 1dir -n 16 -q --server " + server.address() + " -o " + space);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto values = ReadNpy(space);
  ASSERT_TRUE(values.ok()) << values.status().message();
  ASSERT_EQ(values->shape, (std::vector<size_t>{46, 16, 2}));
  ConnectOptions o;
  o.address = server.address();
  auto client = ServiceClient::Connect(o);
  ASSERT_TRUE(client.ok());
  for (int k : {0, 17, 45}) {
    auto set = (*client)->GetAlignedSet(16, {double(k)});
    ASSERT_TRUE(set.ok());
    for (size_t j = 0; j < 16; ++j) {
      EXPECT_EQ(values->values[(k * 16 + j) * 2], set->points[j].x) << k;
      EXPECT_EQ(values->values[(k * 16 + j) * 2 + 1], set->points[j].y) << k;
    }
  }
  // One image with the aligned sets (geometry θ) from that server.
  const std::string img = dir.path() + "/aligned.npy";
  r = e2e::RunCommand(cli + "render --scene shadow --size 32 --sampler aligned-exact -n 16 --server " +
                      server.address() + " -o " + img);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto pixels = ReadNpy(img);
  ASSERT_TRUE(pixels.ok());
  ASSERT_EQ(pixels->shape, (std::vector<size_t>{32, 32}));
  const std::vector<double> ref = MakeShadowScene(32, 32, 1).Reference();
  double mse = 0.0;
  for (size_t i = 0; i < ref.size(); ++i) mse += (pixels->values[i] - ref[i]) * (pixels->values[i] - ref[i]) / ref.size();
  EXPECT_LT(mse, 1e-3);  // 16 samples of a [0, 1] integrand: far below 1/16
  EXPECT_GT(mse, 0.0);
}

// A render can read its aligned lattices from a server instead of searching
// for them: the server's generators (the metadata's lattice_generator) give
// the table the local search builds, entry for entry, plain and tent-folded,
// and the command line renders the same image both ways.
TEST(RenderE2e, LatticesFromAServerAreTheLocalSearchsLattices) {
  TempDir dir;
  ServerProcess server(dir.path(), {"--workers", "2", "--threads-per-worker", "1"});
  ASSERT_EQ(server.error(), "");
  auto client = e2e::ConnectTo(server);
  ASSERT_NE(client, nullptr);
  constexpr uint32_t kN = 64;
  const Scene scene = *MakeScene("antialias", 64, 64, 2);
  const std::vector<PixelDirection> exact = GeometryDirections(scene);
  const AlignedPolicy policy;
  const std::set<std::pair<int, int>> pairs = NeededPairs(exact, policy);
  for (bool folded : {false, true}) {
    SCOPED_TRACE(folded ? "tent-lattice" : "lattice");
    auto local = AlignedLatticeTable(kN, {&exact}, policy, DefaultLatticeWindowDeg(folded), 2, nullptr, {}, folded);
    ASSERT_TRUE(local.ok()) << local.status().message();
    auto served = FetchAlignedSets(*client, kN, pairs, {}, folded ? "tent-lattice" : "lattice");
    ASSERT_TRUE(served.ok()) << served.status().message();
    EXPECT_EQ(served->construction, folded ? "tent-lattice" : "lattice");
    EXPECT_EQ(local->construction, served->construction);
    const auto here = local->table->Resolve(kN, local->construction);
    const auto there = served->table->Resolve(kN, served->construction);
    int compared = 0, pairs_compared = 0;
    std::vector<SetChoice> choices;
    for (int deg = 0; deg < 180; ++deg) choices.push_back({SetChoice::Kind::kOne, deg, 0});
    for (const auto& [a, b] : pairs) choices.push_back({SetChoice::Kind::kTwo, a, b});
    for (const SetChoice& c : choices) {
      if (!local->table->Holds(here, c)) continue;
      ASSERT_TRUE(served->table->Holds(there, c)) << c.a << ", " << c.b;
      const TableSet mine = *local->table->Find(here, c), theirs = *served->table->Find(there, c);
      EXPECT_EQ(mine.n, theirs.n);
      EXPECT_EQ(mine.lattice_generator, theirs.lattice_generator) << c.a << ", " << c.b;
      EXPECT_EQ(mine.folded, folded);
      EXPECT_EQ(theirs.folded, folded);
      ++compared;
      pairs_compared += c.kind == SetChoice::Kind::kTwo;
    }
    EXPECT_GE(compared, 20);  // the image's degrees and pairs, not a vacuous check
    EXPECT_GT(pairs_compared, 0);
  }
  EXPECT_EQ(FetchAlignedSets(*client, kN, pairs, {}, "net").status().code(), Status::Code::kInvalidArgument);

  const std::string cli = std::string(ALIGNSET_CLI_PATH) + " render --scene shadow --size 32 -n 64 -s 3 ";
  const std::string here = dir.path() + "/local.npy", there = dir.path() + "/served.npy";
  auto r = e2e::RunCommand(cli + "--sampler aligned-tent-lattice-exact -o " + here);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = e2e::RunCommand(cli + "--sampler aligned-tent-lattice-exact --lattices server --server " + server.address() +
                      " -o " + there);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto a = ReadNpy(here), b = ReadNpy(there);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->values, b->values);
  // The server's window is fixed, and only lattice samplers read lattices.
  r = e2e::RunCommand(cli + "--sampler aligned-lattice-exact --lattices server --lattice-window 2 --server " +
                      server.address() + " -o " + there);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("--lattice-window needs local lattices"), std::string::npos) << r.output;
  r = e2e::RunCommand(cli + "--sampler owen-sobol --lattices server --server " + server.address() + " -o " + there);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("aligned-lattice"), std::string::npos) << r.output;
}

// The renderer estimates in process (core/analysis); a renderer without the
// core library would send the same pre-pass to the server's EstimateDirection.
// Both must say the same of the same pixels.
TEST(RenderE2e, TheEstimateOverTheWireIsTheInProcessOne) {
  TempDir dir;
  ServerProcess server(dir.path(), {"--workers", "1", "--threads-per-worker", "1"});
  ASSERT_EQ(server.error(), "");
  ConnectOptions o;
  o.address = server.address();
  auto client = ServiceClient::Connect(o);
  ASSERT_TRUE(client.ok()) << client.status().message();
  const Scene scene = *MakeScene("shadow", 128, 128, 1);
  const std::vector<PixelClass> classes = scene.Classes();
  const auto estimator = MakeSpectralEstimator(*ParsePrepass("grid16"));
  int edges = 0, found = 0;
  for (size_t k = 0; k < classes.size() && edges < 12; ++k) {
    const size_t i = (k * 7919 + 101) % classes.size();
    if (classes[i] != PixelClass::kEdge) continue;
    ++edges;
    // grid16: f at the cell centres, row j along y, as GridPatch lays it out.
    std::vector<double> values;
    for (int j = 0; j < 16; ++j) {
      for (int c = 0; c < 16; ++c) values.push_back(scene.Pixel(i).Eval({(c + 0.5) / 16, (j + 0.5) / 16}));
    }
    auto wire = (*client)->EstimateDirection(16, 16, values, /*second=*/true);
    ASSERT_TRUE(wire.ok()) << wire.status().message();
    const PixelDirection local = estimator->Estimate(scene.Pixel(i), HashCombine(1, i));
    ASSERT_EQ(wire->first.found, local.kind != PixelDirection::Kind::kNone) << "pixel " << i;
    if (!wire->first.found) continue;
    ++found;
    EXPECT_NEAR(wire->first.theta_deg, local.theta1, 1e-9) << "pixel " << i;
    EXPECT_NEAR(wire->first.confidence, local.confidence, 1e-12) << "pixel " << i;
    const bool two = wire->has_second && wire->second.found;
    ASSERT_EQ(two, local.kind == PixelDirection::Kind::kTwo) << "pixel " << i;
    if (two) {
      EXPECT_NEAR(wire->second.theta_deg, local.theta2, 1e-9) << "pixel " << i;
    }
  }
  EXPECT_EQ(edges, 12);
  EXPECT_GE(found, 8);  // most edge pixels have a direction: the comparison is not vacuous
}

TEST(RenderE2e, AServerThatIsGoneIsAClearError) {
  ConnectOptions o;
  o.address = "127.0.0.1:1";  // nothing listens there
  o.timeout_seconds = 5;
  auto client = ServiceClient::Connect(o);
  ASSERT_TRUE(client.ok());
  auto table = FetchAlignedSets(**client, 16, {}, nullptr);
  ASSERT_FALSE(table.ok());
  EXPECT_NE(table.status().message().find("UNAVAILABLE"), std::string::npos) << table.status().message();
}

}  // namespace
}  // namespace alignset::render
