// Constructions: a request may ask for an aligned rank-1 lattice instead of
// the optimized set. The real server on loopback serves it as a lattice
// (N-rooks, one generator coprime to N), caches it under a profile of its
// own, aligns it by swap / mirror like any canonical set, refuses unknown
// names with INVALID_ARGUMENT, and never answers one construction with the
// other. Through the client library, raw stubs (Watch, batch, Precompute)
// and the CLI.
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <alignset/client.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <memory>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include "alignset/v1/alignset.grpc.pb.h"
#include "core/align/canonical.h"
#include "core/analysis/integrands.h"
#include "core/analysis/lattice_variance.h"
#include "core/optimize/aligned_lattice.h"
#include "core/optimize/lattice_sequence.h"
#include "core/sampling/rank1_lattice.h"
#include "tests/e2e/e2e_util.h"
#include "tests/e2e/server_process.h"
#include "tests/net_intervals.h"

namespace alignset::e2e {
namespace {

const std::vector<std::string> kFlags = {"--max-iterations", "60", "--workers", "2",
                                         "--threads-per-worker", "1", "--max-n", "4096"};
constexpr const char* kLatticeProfile = "lattice-v2-w1";

AlignedSet MustGet(ServiceClient& client, uint32_t n, double dir, const std::string& construction,
                   uint32_t realization = 0) {
  alignset::SetRequest r;
  r.n = n;
  r.directions_deg = {dir};
  r.realization = realization;
  r.construction = construction;
  auto s = client.GetAlignedSet(r);
  EXPECT_TRUE(s.ok()) << s.status().message();
  return s.ok() ? std::move(s).value() : AlignedSet{};
}

// The generator g when `points` is a centred rank-1 lattice of n points,
// {((i + sx + 1/2) / n, (i g + sy + 1/2) / n)}: one point in the middle of
// every column and every row, and, column by column, the row advancing by
// the same g mod n, coprime to n. Otherwise nullopt, and `why` says what
// failed.
std::optional<uint32_t> LatticeGenerator(const PointSet& points, uint32_t n, std::string* why) {
  if (points.size() != n) {
    *why = "size " + std::to_string(points.size());
    return std::nullopt;
  }
  std::vector<int64_t> row_of_column(n, -1);
  std::vector<int> rows(n, 0);
  for (const Point2& p : points) {
    const double cx = p.x * n - 0.5, cy = p.y * n - 0.5;
    const int64_t c = std::llround(cx), r = std::llround(cy);
    if (std::fabs(cx - c) > 1e-6 || std::fabs(cy - r) > 1e-6 || c < 0 || r < 0 || c >= n || r >= n) {
      *why = "a point off the cell centres: " + std::to_string(p.x) + " " + std::to_string(p.y);
      return std::nullopt;
    }
    if (row_of_column[c] >= 0) {
      *why = "two points in column " + std::to_string(c);
      return std::nullopt;
    }
    row_of_column[c] = r;
    if (++rows[r] > 1) {
      *why = "two points in row " + std::to_string(r);
      return std::nullopt;
    }
  }
  const int64_t g = ((row_of_column[1] - row_of_column[0]) % n + n) % n;
  for (uint32_t c = 0; c < n; ++c) {
    const int64_t step = ((row_of_column[(c + 1) % n] - row_of_column[c]) % n + n) % n;
    if (step != g) {
      *why = "column " + std::to_string(c) + " steps " + std::to_string(step) + ", column 0 " +
             std::to_string(g);
      return std::nullopt;
    }
  }
  if (std::gcd(g, int64_t{n}) != 1) {
    *why = "generator " + std::to_string(g) + " shares a factor with " + std::to_string(n);
    return std::nullopt;
  }
  return static_cast<uint32_t>(g);
}

uint32_t InverseMod(uint32_t g, uint32_t n) {
  for (uint32_t h = 1; h < n; ++h) {
    if (uint64_t{g} * h % n == 1) return h;
  }
  return 0;
}

// The exact Cranley-Patterson variance of the lattice on step edges with
// normals theta + {-1, -0.5, 0, 0.5, 1} degrees (offset 0.07 from the centre,
// an offset the generator search does not score), summed.
double WindowVariance(uint32_t n, uint32_t g, double theta) {
  double sum = 0.0;
  for (double off : {-1.0, -0.5, 0.0, 0.5, 1.0}) {
    auto f = MakeIntegrand("step:" + std::to_string(theta + off) + ":0.07");
    EXPECT_TRUE(f.ok());
    if (!f.ok()) return 0.0;
    sum += Rank1CpVariance(n, g, **f, static_cast<int>(n)).extrapolated;
  }
  return sum;
}

// Most tests need one server of kFlags on a fresh database and a client.
class Constructions : public ::testing::Test {
 protected:
  void SetUp() override {
    server_ = std::make_unique<ServerProcess>(dir_.path(), kFlags);
    ASSERT_EQ(server_->error(), "");
    client_ = ConnectTo(*server_);
    ASSERT_NE(client_, nullptr);
  }

  TempDir dir_;
  std::unique_ptr<ServerProcess> server_;
  std::unique_ptr<ServiceClient> client_;
};

// (a) N = 1024 at 30 degrees: a rank-1 lattice, the one the core chooses for
// 30 degrees (realization 0 = seed 0), stored under the lattice profile; the
// same call again is a cache hit with identical bytes.
TEST_F(Constructions, LatticeIsARank1LatticeAndTheSecondCallIsAHit) {
  const uint32_t n = 1024;
  const AlignedSet first = MustGet(*client_, n, 30.0, "lattice");
  ASSERT_EQ(first.points.size(), n);
  std::string why;
  const auto g = LatticeGenerator(first.points, n, &why);
  ASSERT_TRUE(g.has_value()) << why;
  auto choice = ChooseAlignedLatticeGenerator(n, {30.0});
  ASSERT_TRUE(choice.ok());
  EXPECT_EQ(*g, choice->generator);
  // 30 degrees is canonical: the served set is the stored one as it is.
  EXPECT_EQ(first.points, Align(Rank1LatticePoints(n, choice->generator, 0), AlignOps{}));
  EXPECT_EQ(first.info.construction, "lattice");
  EXPECT_EQ(first.info.profile, kLatticeProfile);
  EXPECT_NE(first.info.key_text.find(std::string("profile=") + kLatticeProfile), std::string::npos)
      << first.info.key_text;
  EXPECT_EQ(first.info.engine, "lattice");
  EXPECT_EQ(first.info.iterations, 0);
  EXPECT_EQ(first.info.loss_total, 0.0);
  EXPECT_EQ(first.info.seed, 0u);
  EXPECT_EQ(first.info.algorithm_version, 2);  // kLatticeAlgorithmVersion
  EXPECT_FALSE(first.info.from_cache);

  const AlignedSet second = MustGet(*client_, n, 30.0, "lattice");
  EXPECT_TRUE(second.info.from_cache);
  EXPECT_EQ(second.raw, first.raw);

  // Realization 1: the same lattice, shifted by whole cells.
  const AlignedSet r1 = MustGet(*client_, n, 30.0, "lattice", 1);
  EXPECT_NE(r1.raw, first.raw);
  EXPECT_EQ(r1.info.seed, 1u);
  const auto g1 = LatticeGenerator(r1.points, n, &why);
  ASSERT_TRUE(g1.has_value()) << why;
  EXPECT_EQ(*g1, *g);

  // The metadata tells the generator, for every realization.
  EXPECT_EQ(first.info.lattice_generator, *g);
  EXPECT_EQ(r1.info.lattice_generator, *g);

  const ServiceMetrics m = client_->GetMetrics().value();
  EXPECT_EQ(m.optimizations_completed, 2u);  // realization 0 and 1, once each

  // A server started on the same SQLite file reads the set back and tells
  // the same generator (read back from the stored points).
  client_.reset();
  EXPECT_EQ(server_->Stop(SIGTERM), 0);
  ServerProcess restarted(dir_.path(), kFlags);
  ASSERT_EQ(restarted.error(), "");
  auto again = ConnectTo(restarted);
  const AlignedSet stored = MustGet(*again, n, 30.0, "lattice", 1);
  EXPECT_TRUE(stored.info.from_cache);
  EXPECT_EQ(stored.raw, r1.raw);
  EXPECT_EQ(stored.info.lattice_generator, *g);
}

// (b) 60 (swap), 150 (mirror) and 120 (both) are the canonical 30-degree
// lattice aligned: lattices with the swapped / mirrored generator, exactly
// as good on their own edges as the 30-degree one on its edges, and each
// better than the unaligned best-Korobov lattice there.
TEST_F(Constructions, SwappedAndMirroredDirectionsGetTheAlignedImagesOfOneLattice) {
  const uint32_t n = 1024;
  const uint32_t korobov = Rank1Generator(n);
  std::string why;
  const AlignedSet base = MustGet(*client_, n, 30.0, "lattice");
  const auto g30 = LatticeGenerator(base.points, n, &why);
  ASSERT_TRUE(g30.has_value()) << why;
  const double v30 = WindowVariance(n, *g30, 30.0);
  for (double theta : {30.0, 60.0, 150.0, 120.0}) {
    SCOPED_TRACE(theta);
    const AlignedSet s = MustGet(*client_, n, theta, "lattice");
    EXPECT_EQ(s.info.profile, kLatticeProfile);
    EXPECT_EQ(s.info.phi1, 30);
    EXPECT_TRUE(s.info.from_cache);  // one canonical set: every direction is a hit
    const auto g = LatticeGenerator(s.points, n, &why);
    ASSERT_TRUE(g.has_value()) << why;
    // Swap first (x <-> y: generator g^-1), then mirror x (generator n - g).
    uint32_t expected = *g30;
    if (s.info.swapped) expected = InverseMod(expected, n);
    if (s.info.inverted) expected = n - expected;
    if (s.info.inverted_y) expected = n - expected;
    EXPECT_EQ(*g, expected) << "swapped " << s.info.swapped << " inverted " << s.info.inverted;
    // The metadata tells the served set's generator without a search.
    EXPECT_EQ(s.info.lattice_generator, *g);
    EXPECT_EQ(s.info.swapped, theta == 60.0 || theta == 120.0);
    EXPECT_EQ(s.info.inverted, theta == 150.0 || theta == 120.0);
    const double aligned = WindowVariance(n, *g, theta);
    EXPECT_NEAR(aligned, v30, 1e-9 * v30);
    const double plain = WindowVariance(n, korobov, theta);
    EXPECT_LT(aligned, 0.9 * plain) << "g " << *g << " Korobov " << korobov;
  }
}

// (b') The tent-folded lattice over the real server: 30 degrees is the
// folded lattice the core chooses (realization r folded after the shift of
// seed r), under its own profile; 150 degrees (a mirror) is the same set
// mirrored, again a folded lattice of that generator (a half shift before
// the fold), and the plain lattice of the same key is another set.
TEST_F(Constructions, TentLatticeIsTheFoldedLatticeAndItsMirrorImage) {
  const uint32_t n = 256;
  AlignedLatticeOptions folded;
  folded.folded = true;
  folded.window_deg = kTentLatticeWindowDeg;
  auto choice = ChooseAlignedLatticeGenerator(n, {30.0}, folded);
  ASSERT_TRUE(choice.ok());
  const AlignedSet first = MustGet(*client_, n, 30.0, "tent-lattice", 2);
  EXPECT_EQ(first.points, TentLatticePoints(n, choice->generator, 2));
  EXPECT_EQ(first.info.construction, "tent-lattice");
  EXPECT_EQ(first.info.profile, "tent-lattice-v1-w2");
  EXPECT_EQ(first.info.engine, "tent-lattice");
  EXPECT_EQ(first.info.algorithm_version, 1);
  EXPECT_EQ(first.info.seed, 2u);
  EXPECT_EQ(first.info.lattice_generator, choice->generator);
  const AlignedSet mirrored = MustGet(*client_, n, 150.0, "tent-lattice", 2);
  // Mirrored, the served generator is N - g (for a folded lattice g and
  // N - g give the same sets under other shifts); swapped, g^-1.
  EXPECT_EQ(mirrored.info.lattice_generator, n - choice->generator);
  const AlignedSet swapped = MustGet(*client_, n, 60.0, "tent-lattice", 2);
  EXPECT_TRUE(swapped.info.swapped);
  EXPECT_EQ(swapped.info.lattice_generator, InverseMod(choice->generator, n));
  EXPECT_TRUE(mirrored.info.from_cache);
  EXPECT_TRUE(mirrored.info.inverted);
  ASSERT_EQ(mirrored.points.size(), n);
  for (uint32_t i = 0; i < n; ++i) {
    EXPECT_NEAR(mirrored.points[i].x, 1.0 - first.points[i].x, 1e-12);
    EXPECT_EQ(mirrored.points[i].y, first.points[i].y);
  }
  EXPECT_NE(MustGet(*client_, n, 30.0, "lattice", 2).raw, first.raw);
}

// (c) An unknown construction is INVALID_ARGUMENT on every call that takes
// one, with the known names in the message, and the server keeps serving.
TEST_F(Constructions, UnknownNamesAreInvalidArgumentAndTheServerKeepsServing) {
  auto stub = OwnStub(server_->address());
  auto names_the_known = [](const std::string& message) {
    return message.find("'optimized'") != std::string::npos &&
           message.find("'lattice'") != std::string::npos && message.find("'net'") != std::string::npos;
  };
  v1::AlignedSetRequest bad = SetRequest(256, {30.0});
  bad.set_construction("sobol");
  {
    grpc::ClientContext ctx;
    v1::AlignedSetResponse resp;
    const grpc::Status s = stub->GetAlignedSet(&ctx, bad, &resp);
    EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_TRUE(names_the_known(s.error_message())) << s.error_message();
    EXPECT_NE(s.error_message().find("'sobol'"), std::string::npos) << s.error_message();
  }
  {
    grpc::ClientContext ctx;
    auto reader = stub->WatchAlignedSet(&ctx, bad);
    v1::WatchEvent ev;
    while (reader->Read(&ev)) {
    }
    const grpc::Status s = reader->Finish();
    EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_TRUE(names_the_known(s.error_message())) << s.error_message();
  }
  {
    // A batch: the bad item fails alone.
    v1::AlignedSetsRequest req;
    *req.add_items() = bad;
    v1::AlignedSetRequest good = SetRequest(256, {40.0});
    good.set_construction("lattice");
    *req.add_items() = good;
    grpc::ClientContext ctx;
    v1::AlignedSetsResponse resp;
    ASSERT_TRUE(stub->GetAlignedSets(&ctx, req, &resp).ok());
    ASSERT_EQ(resp.items_size(), 2);
    EXPECT_EQ(resp.items(0).code(), static_cast<int>(grpc::StatusCode::INVALID_ARGUMENT));
    EXPECT_TRUE(names_the_known(resp.items(0).message())) << resp.items(0).message();
    EXPECT_EQ(resp.items(1).code(), 0) << resp.items(1).message();
    EXPECT_EQ(resp.items(1).set().metadata().construction(), "lattice");
  }
  {
    // A space batch: refused as a whole.
    v1::AlignedSetsRequest req;
    req.set_space(v1::ONE_DIRECTION);
    req.set_space_n(64);
    req.set_space_construction("Lattice");
    grpc::ClientContext ctx;
    v1::AlignedSetsResponse resp;
    const grpc::Status s = stub->GetAlignedSets(&ctx, req, &resp);
    EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_TRUE(names_the_known(s.error_message())) << s.error_message();
  }
  {
    v1::PrecomputeRequest req;
    req.add_n(64);
    req.set_space(v1::ONE_DIRECTION);
    req.set_construction("random");
    grpc::ClientContext ctx;
    auto reader = stub->Precompute(&ctx, req);
    v1::PrecomputeProgress p;
    while (reader->Read(&p)) {
    }
    const grpc::Status s = reader->Finish();
    EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_TRUE(names_the_known(s.error_message())) << s.error_message();
  }
  // Still serving, both constructions.
  EXPECT_EQ(MustGet(*client_, 256, 30.0, "lattice").info.construction, "lattice");
  EXPECT_EQ(MustGet(*client_, 256, 30.0, "optimized").info.construction, "optimized");
  EXPECT_EQ(MustGet(*client_, 256, 30.0, "").info.construction, "optimized");
  EXPECT_GE(GetMetrics(server_->address()).requests_invalid(), 5u);
}

// (d) The optimized set of a key whose lattice is cached is optimized, not
// the lattice; and the lattice is still the lattice afterwards.
TEST_F(Constructions, AnOptimizedRequestIsNeverAnsweredWithTheLattice) {
  const AlignedSet lattice = MustGet(*client_, 256, 30.0, "lattice");
  const AlignedSet optimized = MustGet(*client_, 256, 30.0, "");
  EXPECT_NE(optimized.raw, lattice.raw);
  EXPECT_NE(optimized.info.profile, lattice.info.profile);
  EXPECT_EQ(optimized.info.construction, "optimized");
  EXPECT_FALSE(optimized.info.from_cache);
  EXPECT_NE(optimized.info.engine, "lattice");
  EXPECT_GT(optimized.info.iterations, 0);
  EXPECT_EQ(optimized.info.lattice_generator, 0u);
  std::string why;
  EXPECT_FALSE(LatticeGenerator(optimized.points, 256, &why).has_value());
  const AlignedSet again = MustGet(*client_, 256, 30.0, "lattice");
  EXPECT_TRUE(again.info.from_cache);
  EXPECT_EQ(again.raw, lattice.raw);
  const AlignedSet optimized_again = MustGet(*client_, 256, 30.0, "optimized");
  EXPECT_TRUE(optimized_again.info.from_cache);
  EXPECT_EQ(optimized_again.raw, optimized.raw);
  // Two sets cached, one per profile.
  auto lattices = client_->ListCachedSets(256, kLatticeProfile, 0);
  ASSERT_TRUE(lattices.ok());
  EXPECT_EQ(lattices->size(), 1u);
  auto all = client_->ListCachedSets(256, "", 0);
  ASSERT_TRUE(all.ok());
  EXPECT_EQ(all->size(), 2u);
}

// Watch, batch (items and the space) and Precompute take the construction.
TEST_F(Constructions, WatchBatchAndPrecomputeServeLattices) {
  std::string why;

  PrecomputeSpec spec;
  spec.n = {256};
  spec.space = 0;
  spec.keys = {{10}, {20}};
  spec.realizations = 2;
  spec.construction = "lattice";
  auto done = client_->Precompute(spec, nullptr);
  ASSERT_TRUE(done.ok()) << done.status().message();
  EXPECT_EQ(done->total, 4u);
  EXPECT_EQ(done->done, 4u);
  EXPECT_EQ(done->failed, 0u);
  auto rerun = client_->Precompute(spec, nullptr);
  ASSERT_TRUE(rerun.ok()) << rerun.status().message();
  EXPECT_EQ(rerun->cached_already, 4u);
  // 100 degrees is 10 swapped: served from what precompute stored.
  alignset::SetRequest watch;
  watch.n = 256;
  watch.directions_deg = {100.0};
  watch.realization = 1;
  watch.construction = "lattice";
  auto watched = client_->WatchAlignedSet(watch, nullptr);
  ASSERT_TRUE(watched.ok()) << watched.status().message();
  EXPECT_TRUE(watched->info.from_cache);
  EXPECT_EQ(watched->info.construction, "lattice");
  EXPECT_TRUE(watched->info.swapped);
  EXPECT_TRUE(LatticeGenerator(watched->points, 256, &why).has_value()) << why;
  // A new key through Watch: a set, no progress needed.
  watch.directions_deg = {33.0};
  watched = client_->WatchAlignedSet(watch, nullptr);
  ASSERT_TRUE(watched.ok()) << watched.status().message();
  EXPECT_FALSE(watched->info.from_cache);
  EXPECT_TRUE(LatticeGenerator(watched->points, 256, &why).has_value()) << why;

  std::vector<alignset::SetRequest> items(3);
  for (size_t i = 0; i < items.size(); ++i) {
    items[i].n = 128;
    items[i].directions_deg = {12.0 + 40.0 * static_cast<double>(i), 100.0};
    items[i].construction = "lattice";
  }
  auto batch = client_->GetAlignedSets(items);
  ASSERT_TRUE(batch.ok()) << batch.status().message();
  for (const BatchItem& item : *batch) {
    ASSERT_TRUE(item.status.ok()) << item.status.message();
    EXPECT_EQ(item.set.info.direction_count, 2);
    EXPECT_EQ(item.set.info.construction, "lattice");
    EXPECT_TRUE(LatticeGenerator(item.set.points, 128, &why).has_value()) << why;
  }

  auto stub = OwnStub(server_->address());
  v1::AlignedSetsRequest req;
  req.set_space(v1::ONE_DIRECTION);
  req.set_space_n(64);
  req.set_space_construction("lattice");
  grpc::ClientContext ctx;
  v1::AlignedSetsResponse resp;
  ASSERT_TRUE(stub->GetAlignedSets(&ctx, req, &resp).ok());
  ASSERT_EQ(resp.items_size(), 46);
  for (const auto& item : resp.items()) {
    ASSERT_EQ(item.code(), 0) << item.message();
    EXPECT_EQ(item.set().metadata().key().profile(), kLatticeProfile);
  }
}

// A read-only replica serves lattices from its shipped file, and fills a
// missing one from its writer as a lattice (not the writer's optimized set).
TEST(ConstructionReplicas, AReplicaServesAndFillsLattices) {
  TempDir shipped, writer_dir, replica_dir;
  std::string file;
  {
    ServerProcess maker(shipped.path(), kFlags);
    ASSERT_EQ(maker.error(), "");
    file = maker.db_path();
    MustGet(*ConnectTo(maker), 64, 10.0, "lattice");
  }
  ServerProcess writer(writer_dir.path(), kFlags);
  ASSERT_EQ(writer.error(), "");
  std::vector<std::string> flags = kFlags;
  for (const char* f : {"--read-only", "--db"}) flags.push_back(f);
  flags.push_back(file);
  flags.push_back("--fill-from");
  flags.push_back(writer.address());
  ServerProcess replica(replica_dir.path(), flags);
  ASSERT_EQ(replica.error(), "");
  auto rc = ConnectTo(replica);
  auto wc = ConnectTo(writer);
  const AlignedSet shipped_set = MustGet(*rc, 64, 10.0, "lattice");
  EXPECT_TRUE(shipped_set.info.from_cache);
  std::string why;
  EXPECT_TRUE(LatticeGenerator(shipped_set.points, 64, &why).has_value()) << why;
  const AlignedSet filled = MustGet(*rc, 128, 77.25, "lattice");
  EXPECT_EQ(filled.info.construction, "lattice");
  const auto filled_generator = LatticeGenerator(filled.points, 128, &why);
  ASSERT_TRUE(filled_generator.has_value()) << why;
  EXPECT_EQ(filled.info.lattice_generator, *filled_generator);  // read back on the replica
  const AlignedSet from_writer = MustGet(*wc, 128, 77.25, "lattice");
  EXPECT_TRUE(from_writer.info.from_cache);  // made for the replica
  EXPECT_EQ(filled.raw, from_writer.raw);
  EXPECT_EQ(GetMetrics(replica.address()).sets_filled(), 1u);
}

// The CLI: get and precompute with --construction.
TEST_F(Constructions, CliGetAndPrecomputeTakeConstruction) {
  const std::string cli = std::string(ALIGNSET_CLI_PATH) + " ";
  const std::string at = " --server " + server_->address();
  auto pre = RunCommand(cli + "precompute" + at + " --n 128 --space keys --key 30 --key 40 --construction lattice");
  ASSERT_EQ(pre.exit_code, 0) << pre.output;
  EXPECT_NE(pre.output.find("constructed    2"), std::string::npos) << pre.output;
  const std::string out = dir_.path() + "/lattice.txt";
  auto get = RunCommand(cli + "get" + at + " --n 128 --dir 130 --construction lattice --quiet --out " + out);
  ASSERT_EQ(get.exit_code, 0) << get.output;
  EXPECT_NE(get.output.find("construction   aligned rank-1 lattice"), std::string::npos) << get.output;
  EXPECT_NE(get.output.find("from cache     yes"), std::string::npos) << get.output;
  EXPECT_NE(get.output.find(kLatticeProfile), std::string::npos) << get.output;
  std::ifstream in(out);
  PointSet points;
  std::string comment;
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    if (line[0] == '#') {
      comment += line;
      continue;
    }
    Point2 p;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf %lf", &p.x, &p.y), 2) << line;
    points.push_back(p);
  }
  EXPECT_NE(comment.find("construction=lattice"), std::string::npos) << comment;
  std::string why;
  EXPECT_TRUE(LatticeGenerator(points, 128, &why).has_value()) << why;

  auto space = RunCommand(cli + "get" + at + " --n 64 --space 1dir --construction lattice --quiet --out " +
                          dir_.path() + "/space.npy");
  EXPECT_EQ(space.exit_code, 0) << space.output;
  auto optimized = RunCommand(cli + "get" + at + " --n 128 --dir 130 --quiet --out " + out);
  ASSERT_EQ(optimized.exit_code, 0) << optimized.output;
  EXPECT_NE(optimized.output.find("from cache     no"), std::string::npos) << optimized.output;
  EXPECT_EQ(optimized.output.find(kLatticeProfile), std::string::npos) << optimized.output;

  auto bad = RunCommand(cli + "get" + at + " --n 128 --dir 30 --construction sobol --out " + out);
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("lattice"), std::string::npos) << bad.output;
}

// Nets: the served set is a (0,m,2)-net at every power of two (every
// elementary interval counted), its own profile, a hit the second time with
// the same bytes, the mirrored direction its aligned image; an N that is not
// a power of two is INVALID_ARGUMENT and the server keeps serving.
TEST_F(Constructions, NetIsANetAtEveryPowerOfTwoAndTheSecondCallIsAHit) {
  const AlignedSet first = MustGet(*client_, 256, 30.0, "net");
  EXPECT_EQ(first.info.construction, "net");
  EXPECT_EQ(first.info.engine, "net");
  EXPECT_EQ(first.info.profile, "net-v1-w1");
  EXPECT_FALSE(first.info.from_cache);
  EXPECT_EQ(testing::PrefixNetViolation(first.points), "");
  const AlignedSet again = MustGet(*client_, 256, 30.0, "net");
  EXPECT_TRUE(again.info.from_cache);
  ASSERT_EQ(again.points.size(), first.points.size());
  for (size_t i = 0; i < first.points.size(); ++i) {
    ASSERT_EQ(again.points[i].x, first.points[i].x);
    ASSERT_EQ(again.points[i].y, first.points[i].y);
  }
  // 150 degrees is 30 mirrored (x -> 1 - x): the same canonical net.
  const AlignedSet mirrored = MustGet(*client_, 256, 150.0, "net");
  EXPECT_TRUE(mirrored.info.from_cache);
  EXPECT_EQ(testing::PrefixNetViolation(mirrored.points), "");
  // An optimized request for the same key is not answered with the net.
  const AlignedSet optimized = MustGet(*client_, 256, 30.0, "");
  EXPECT_EQ(optimized.info.construction, "optimized");
  EXPECT_FALSE(optimized.info.from_cache);

  alignset::SetRequest bad;
  bad.n = 100;
  bad.directions_deg = {30.0};
  bad.construction = "net";
  auto refused = client_->GetAlignedSet(bad);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), Status::Code::kInvalidArgument);
  EXPECT_NE(refused.status().message().find("power of two"), std::string::npos) << refused.status().message();
  EXPECT_EQ(MustGet(*client_, 64, 45.0, "net").points.size(), 64u);  // still serving
}


// The lattice sequence by name: the set for N is the first N points of the
// set for a larger N (same key, same realization), at the canonical 30
// degrees the core's sequence for 30 degrees bit for bit, at 150 degrees its
// mirror image; N outside [16, 65536] refused and the server keeps serving.
TEST_F(Constructions, LatticeSequenceServesPrefixesOfOneSequence) {
  const AlignedSet small = MustGet(*client_, 256, 30.0, "lattice-sequence");
  const AlignedSet large = MustGet(*client_, 1024, 30.0, "lattice-sequence");
  EXPECT_EQ(small.info.construction, "lattice-sequence");
  EXPECT_EQ(small.info.profile, "lattice-sequence-v1-w1");
  ASSERT_EQ(small.points.size(), 256u);
  ASSERT_EQ(large.points.size(), 1024u);
  for (size_t i = 0; i < small.points.size(); ++i) ASSERT_EQ(small.points[i], large.points[i]) << i;
  // The sequence of one generator under realization 0's shift: point 512
  // is point 0 moved by (1, g) / 1024, which gives g mod 1024, and the first
  // 1024 points depend on nothing else (the core's search is tested there).
  const double gy = large.points[512].y - large.points[0].y;
  const uint32_t g = static_cast<uint32_t>(std::llround((gy - std::floor(gy)) * 1024.0)) % 1024;
  EXPECT_EQ(large.points, LatticeSequencePoints(1024, g, 0)) << "g mod 1024 = " << g;
  const AlignedSet mirrored = MustGet(*client_, 512, 150.0, "lattice-sequence");
  ASSERT_EQ(mirrored.points.size(), 512u);
  for (size_t i = 0; i < mirrored.points.size(); ++i) {
    // x -> 1 - x (a point at x = 0 stays in the half-open square as the
    // server's mirror keeps it).
    const double d = std::fmod(mirrored.points[i].x + large.points[i].x, 1.0);
    EXPECT_LT(std::min(d, 1.0 - d), 1e-12) << i;
    EXPECT_EQ(mirrored.points[i].y, large.points[i].y) << i;
  }
  // Realization 1: another shift of the same sequence.
  const AlignedSet r1 = MustGet(*client_, 256, 30.0, "lattice-sequence", 1);
  EXPECT_EQ(r1.points, LatticeSequencePoints(256, g, 1));

  alignset::SetRequest bad;
  bad.n = 8;
  bad.directions_deg = {30.0};
  bad.construction = "lattice-sequence";
  auto refused = client_->GetAlignedSet(bad);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), Status::Code::kInvalidArgument);
  EXPECT_EQ(MustGet(*client_, 64, 60.0, "lattice-sequence").points.size(), 64u);  // still serving
}

}  // namespace
}  // namespace alignset::e2e
