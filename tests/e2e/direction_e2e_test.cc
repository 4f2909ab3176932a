// End-to-end: EstimateDirection and the quarter-degree canonical grid on the
// real alignset-server binary over loopback.
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <cstdlib>
#include <cstdio>
#include <algorithm>
#include <limits>

#include "alignset/v1/alignset.grpc.pb.h"
#include "client/service_client.h"
#include "tests/client/npy_test_file.h"
#include "tests/e2e/server_process.h"

namespace alignset::e2e {
namespace {

using cli::ServiceClient;

const std::vector<std::string> kFast = {"--max-iterations", "60", "--workers", "2",
                                        "--threads-per-worker", "1", "--max-n", "4096"};

class DirectionE2eTest : public ::testing::Test {
 protected:
  void StartServer(const std::vector<std::string>& flags) {
    server_.reset();
    server_ = std::make_unique<ServerProcess>(dir_.path(), flags);
    ASSERT_EQ(server_->error(), "");
  }
  std::unique_ptr<ServiceClient> Client() { return ConnectTo(*server_); }
  std::unique_ptr<v1::AlignSet::Stub> RawStub() {
    grpc::ChannelArguments args;
    args.SetMaxSendMessageSize(-1);
    args.SetMaxReceiveMessageSize(-1);
    return v1::AlignSet::NewStub(
        grpc::CreateCustomChannel(server_->address(), grpc::InsecureChannelCredentials(), args));
  }
  TempDir dir_;
  std::unique_ptr<ServerProcess> server_;
};

// A step edge with normal theta through the centre, sampled at cell centres.
std::vector<double> StepGrid(int w, int h, double theta_deg) {
  const double t = theta_deg * M_PI / 180.0;
  std::vector<double> v(static_cast<size_t>(w) * h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const double x = (i + 0.5) / w - 0.5, y = (j + 0.5) / h - 0.5;
      v[static_cast<size_t>(j) * w + i] = x * std::cos(t) + y * std::sin(t) >= 0.03 ? 1.0 : 0.0;
    }
  return v;
}

double AngleError(double a, double b) {
  double d = std::fmod(std::fabs(a - b), 180.0);
  return std::min(d, 180.0 - d);
}

TEST_F(DirectionE2eTest, EstimatesGridsAndSamplesAndSaysWhenThereIsNoDirection) {
  StartServer(kFast);
  auto client = Client();
  auto grid = client->EstimateDirection(64, 64, StepGrid(64, 64, 123.4), false);
  ASSERT_TRUE(grid.ok()) << grid.status().message();
  ASSERT_TRUE(grid->first.found) << grid->first.reason;
  EXPECT_LT(AngleError(grid->first.theta_deg, 123.4), 1.0);
  EXPECT_GT(grid->first.kappa, 0.0);
  EXPECT_GT(grid->first.confidence, 0.0);
  EXPECT_FALSE(grid->has_second);
  EXPECT_EQ(grid->max_radius, 28.0);

  // Scattered samples of the same edge.
  PointSet pts;
  std::vector<double> f;
  uint64_t state = 12345;
  auto uniform = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) * 0x1.0p-53;
  };
  const double t = 123.4 * M_PI / 180.0;
  for (int j = 0; j < 4096; ++j) {
    pts.push_back({uniform(), uniform()});
    f.push_back((pts.back().x - 0.5) * std::cos(t) + (pts.back().y - 0.5) * std::sin(t) >= 0 ? 1.0 : 0.0);
  }
  auto samples = client->EstimateDirection(pts, f, true);
  ASSERT_TRUE(samples.ok()) << samples.status().message();
  ASSERT_TRUE(samples->first.found) << samples->first.reason;
  EXPECT_LT(AngleError(samples->first.theta_deg, 123.4), 3.0);
  EXPECT_TRUE(samples->has_second);

  // A constant patch has no direction, and no angle comes back.
  auto flat = client->EstimateDirection(16, 16, std::vector<double>(256, 0.5), true);
  ASSERT_TRUE(flat.ok());
  EXPECT_FALSE(flat->first.found);
  EXPECT_EQ(flat->first.theta_deg, 0.0);
  EXPECT_NE(flat->first.reason.find("constant"), std::string::npos);
  EXPECT_FALSE(flat->second.found);
}

void ExpectInvalid(const grpc::Status& s, const std::string& fragment) {
  EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << s.error_message();
  EXPECT_NE(s.error_message().find(fragment), std::string::npos) << s.error_message();
}

TEST_F(DirectionE2eTest, BadPatchesGetInvalidArgumentAndTheServerKeepsServing) {
  StartServer(kFast);
  auto stub = RawStub();
  auto call = [&](const v1::EstimateDirectionRequest& req) {
    v1::EstimateDirectionResponse resp;
    grpc::ClientContext ctx;
    return stub->EstimateDirection(&ctx, req, &resp);
  };
  auto grid = [](uint32_t w, uint32_t h, size_t count, double fill = 0.0) {
    v1::EstimateDirectionRequest r;
    r.mutable_grid()->set_width(w);
    r.mutable_grid()->set_height(h);
    for (size_t i = 0; i < count; ++i) r.mutable_grid()->add_values(fill);
    return r;
  };
  ExpectInvalid(call({}), "give a grid of values or scattered samples");   // empty
  ExpectInvalid(call(grid(0, 0, 0)), "at least 8 x 8");                    // empty grid
  ExpectInvalid(call(grid(7, 8, 56)), "at least 8 x 8");
  ExpectInvalid(call(grid(10, 10, 64)), "needs 100 values, got 64");       // wrong size
  ExpectInvalid(call(grid(5000, 8, 0)), "at most 4096 cells a side");      // over the limit
  ExpectInvalid(call(grid(2048, 1024, 0)), "1048576 in all");              // over the limit
  auto nan = grid(8, 8, 64);
  nan.mutable_grid()->set_values(10, std::nan(""));
  ExpectInvalid(call(nan), "row 1, column 2");                            // non-finite
  auto inf = grid(8, 8, 64);
  inf.mutable_grid()->set_values(0, std::numeric_limits<double>::infinity());
  ExpectInvalid(call(inf), "not finite");

  v1::EstimateDirectionRequest s;
  s.mutable_samples();
  ExpectInvalid(call(s), "no samples");                                   // empty samples
  s.mutable_samples()->add_x(0.5);
  s.mutable_samples()->add_y(0.5);
  ExpectInvalid(call(s), "as many x as y and f");                         // mismatched
  s.mutable_samples()->add_f(std::nan(""));
  ExpectInvalid(call(s), "not finite");
  s.mutable_samples()->set_f(0, 1.0);
  s.mutable_samples()->set_x(0, 1.5);
  ExpectInvalid(call(s), "outside [0,1]^2");

  // A message over the server's receive limit never reaches the handler.
  auto huge = grid(512, 512, 512 * 512);  // 2 MiB of values, limit 1 MiB
  EXPECT_EQ(call(huge).error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);

  // Still serving: the same RPC and a set.
  auto ok = Client()->EstimateDirection(32, 32, StepGrid(32, 32, 10.0), false);
  ASSERT_TRUE(ok.ok()) << ok.status().message();
  EXPECT_TRUE(ok->first.found);
  auto set = Client()->GetAlignedSet(64, {ok->first.theta_deg});
  ASSERT_TRUE(set.ok()) << set.status().message();
  auto m = Client()->GetMetrics();
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(m->requests_invalid, 12u);
  EXPECT_EQ(m->requests_estimate, 13u);  // the oversized one never arrived
}

TEST_F(DirectionE2eTest, QuarterDegreeGridServesFinerAnglesAndKeepsWholeDegreeRows) {
  StartServer(kFast);  // default --angle-step 0.25
  auto client = Client();
  // A whole-degree set stored by a whole-degree request ...
  auto get = [&](std::vector<double> dirs, uint32_t steps) {
    cli::SetRequest r;
    r.n = 64;
    r.directions_deg = std::move(dirs);
    r.steps_per_degree = steps;
    return client->GetAlignedSet(r);
  };
  auto whole = get({30.0}, 1);
  ASSERT_TRUE(whole.ok()) << whole.status().message();
  EXPECT_FALSE(whole->info.from_cache);
  EXPECT_EQ(whole->info.steps_per_degree, 1);
  EXPECT_EQ(whole->info.key_index, 30u);
  // ... is the same row for the quarter grid's 30.0.
  auto same = client->GetAlignedSet(64, {30.0});
  ASSERT_TRUE(same.ok());
  EXPECT_TRUE(same->info.from_cache);
  EXPECT_EQ(same->raw, whole->raw);
  EXPECT_EQ(same->info.steps_per_degree, 4);
  EXPECT_EQ(same->info.key_index, 120u);

  // 149.8 is served as 149.75 = 180 - 30.25: the quarter key, inverted.
  auto fine = client->GetAlignedSet(64, {149.8});
  ASSERT_TRUE(fine.ok()) << fine.status().message();
  EXPECT_FALSE(fine->info.from_cache);
  EXPECT_EQ(fine->info.served_exact_deg, std::vector<double>{149.75});
  EXPECT_EQ(fine->info.served_deg, std::vector<int>{150});
  EXPECT_EQ(fine->info.phi1_exact, 30.25);
  EXPECT_EQ(fine->info.phi1, 30);
  EXPECT_EQ(fine->info.key_index, 121u);
  EXPECT_TRUE(fine->info.inverted);
  EXPECT_FALSE(fine->info.swapped);
  EXPECT_NE(fine->raw, whole->raw);
  // Asked on whole degrees, 149.8 is 150: the whole-degree row again.
  auto coarse = get({149.8}, 1);
  ASSERT_TRUE(coarse.ok());
  EXPECT_TRUE(coarse->info.from_cache);
  EXPECT_EQ(coarse->info.served_exact_deg, std::vector<double>{150.0});
  // Two directions stay on whole degrees.
  auto two = client->GetAlignedSet(64, {20.3, 100.6});
  ASSERT_TRUE(two.ok());
  EXPECT_EQ(two->info.served_exact_deg, (std::vector<double>{20, 101}));
  // A grid that does not exist.
  auto bad = get({30.0}, 3);
  EXPECT_EQ(bad.status().code(), Status::Code::kInvalidArgument);

  // Precompute on the quarter grid: shard 0 of 60 is the first 181 / 60 = 3
  // keys of the lineage order: the root 1, then its children 0 and 0.75
  // (quarter indices 4, 0, 3). Sets for 1 and 30 are stored already (1 by
  // this request).
  auto one = get({1.0}, 4);
  ASSERT_TRUE(one.ok());
  cli::PrecomputeSpec spec;
  spec.n = {64};
  spec.space = 1;
  spec.steps_per_degree = 4;
  spec.shard_index = 0;
  spec.shard_count = 60;
  auto pre = client->Precompute(spec, nullptr);
  ASSERT_TRUE(pre.ok()) << pre.status().message();
  EXPECT_EQ(pre->total, 3u);
  EXPECT_EQ(pre->cached_already, 1u);
  EXPECT_EQ(pre->done, 2u);
  // The whole-degree space keeps its 46 keys.
  spec.steps_per_degree = 1;
  spec.shard_count = 23;
  auto pre1 = client->Precompute(spec, nullptr);
  ASSERT_TRUE(pre1.ok());
  EXPECT_EQ(pre1->total, 2u);  // indices 0 and 23 of 46
}

TEST_F(DirectionE2eTest, WholeDegreeServerRoundsToWholeDegrees) {
  std::vector<std::string> flags = kFast;
  flags.insert(flags.end(), {"--angle-step", "1"});
  StartServer(flags);
  auto fine = Client()->GetAlignedSet(64, {30.3});
  ASSERT_TRUE(fine.ok()) << fine.status().message();
  EXPECT_EQ(fine->info.served_exact_deg, std::vector<double>{30.0});
  EXPECT_EQ(fine->info.steps_per_degree, 1);
}

// `alignset get --from-patch`: the server estimates the direction, and the
// set for it is served in the same command; a patch without a direction is a
// failure that says so, a bad patch a usage error, and the server serves on.
TEST_F(DirectionE2eTest, CliGetFromPatchEstimatesThenServesThatDirection) {
  StartServer(kFast);
  const std::string cli = std::string(ALIGNSET_CLI_PATH) + " ";
  const std::string server = " --server " + server_->address() + " ";
  const std::string patch = dir_.path() + "/edge.npy";
  test_support::WriteNpy(patch, {64, 64}, StepGrid(64, 64, 33.3));
  const std::string out = dir_.path() + "/set.txt";
  auto got = RunCommand(cli + "get" + server + "--n 64 --from-patch " + patch + " --out " + out);
  ASSERT_EQ(got.exit_code, 0) << got.output;
  const size_t at = got.output.find("estimated theta ");
  ASSERT_NE(at, std::string::npos) << got.output;
  const double theta = std::atof(got.output.c_str() + at + 16);
  EXPECT_LT(AngleError(theta, 33.3), 1.0) << got.output;
  // Served on the server's default quarter-degree grid: the estimate's
  // nearest quarter, exactly what --dir with the estimate serves.
  char served[64];
  std::snprintf(served, sizeof(served), "directions     0, 90, %g ", std::round(theta * 4) / 4);
  EXPECT_NE(got.output.find(served), std::string::npos) << got.output;
  char dir[32];
  std::snprintf(dir, sizeof(dir), "%.4f", theta);
  auto same = RunCommand(cli + "get" + server + "--n 64 --dir " + dir + " --out " + out + "2");
  ASSERT_EQ(same.exit_code, 0) << same.output;
  EXPECT_NE(same.output.find("from cache     yes"), std::string::npos) << same.output;
  EXPECT_NE(same.output.find(served), std::string::npos) << same.output;

  // --angle-step 1 asks for the whole-degree grid instead.
  auto whole = RunCommand(cli + "get" + server + "--n 64 --angle-step 1 --from-patch " + patch +
                          " --out " + out);
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  std::snprintf(served, sizeof(served), "directions     0, 90, %g ", std::round(theta));
  EXPECT_NE(whole.output.find(served), std::string::npos) << whole.output;
  auto step = RunCommand(cli + "precompute" + server + "--n 64 --angle-step 0.3");
  EXPECT_EQ(step.exit_code, 2) << step.output;

  // Two crossing edges with --two: a two-direction set.
  std::vector<double> cross = StepGrid(64, 64, 20.0), other = StepGrid(64, 64, 110.0);
  for (size_t k = 0; k < cross.size(); ++k) cross[k] += 0.5 * other[k];
  const std::string cross_path = dir_.path() + "/cross.npy";
  test_support::WriteNpy(cross_path, {64, 64}, cross);
  auto two = RunCommand(cli + "get" + server + "--n 64 --two --from-patch " + cross_path +
                        " --out " + out);
  ASSERT_EQ(two.exit_code, 0) << two.output;
  EXPECT_NE(two.output.find("directions     0, 90, 20,110 "), std::string::npos) << two.output;

  // No dominant direction: status 1, one line, no set written.
  const std::string flat = dir_.path() + "/flat.npy";
  test_support::WriteNpy(flat, {16, 16}, std::vector<double>(256, 0.25));
  auto none = RunCommand(cli + "get" + server + "--n 64 --from-patch " + flat + " --out " +
                         dir_.path() + "/none.txt");
  EXPECT_EQ(none.exit_code, 1) << none.output;
  EXPECT_EQ(std::count(none.output.begin(), none.output.end(), '\n'), 1) << none.output;
  EXPECT_NE(none.output.find("no dominant direction"), std::string::npos) << none.output;
  EXPECT_FALSE(std::ifstream(dir_.path() + "/none.txt").good());

  // A bad patch is a usage error; --dir and --from-patch do not go together.
  const std::string bad = dir_.path() + "/bad.npy";
  std::vector<double> values = StepGrid(16, 16, 10.0);
  values[3] = std::numeric_limits<double>::quiet_NaN();
  test_support::WriteNpy(bad, {16, 16}, values);
  auto refused = RunCommand(cli + "get" + server + "--n 64 --from-patch " + bad + " --out " + out);
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("not finite"), std::string::npos) << refused.output;
  auto both = RunCommand(cli + "get" + server + "--n 64 --dir 3 --from-patch " + patch + " --out " + out);
  EXPECT_EQ(both.exit_code, 2) << both.output;
  auto neither = RunCommand(cli + "get" + server + "--n 64 --out " + out);
  EXPECT_EQ(neither.exit_code, 2) << neither.output;
  EXPECT_NE(neither.output.find("--from-patch"), std::string::npos) << neither.output;

  auto alive = Client()->Healthy();
  ASSERT_TRUE(alive.ok());
  EXPECT_TRUE(*alive);
}

}  // namespace
}  // namespace alignset::e2e
