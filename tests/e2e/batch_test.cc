// GetAlignedSets (many sets in one call) and per-call deadlines, against the
// real server binary on loopback.
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <alignset/client.h>

#include <chrono>
#include <thread>

#include "alignset/v1/alignset.grpc.pb.h"
#include "tests/e2e/server_process.h"

namespace alignset::e2e {
namespace {

using namespace std::chrono_literals;

const std::vector<std::string> kFast = {"--max-iterations", "60", "--workers", "2",
                                        "--threads-per-worker", "1", "--max-n", "4096"};

class BatchTest : public ::testing::Test {
 protected:
  void StartServer(const std::vector<std::string>& flags) {
    server_ = std::make_unique<ServerProcess>(dir_.path(), flags);
    ASSERT_EQ(server_->error(), "");
  }
  std::unique_ptr<ServiceClient> Client() { return ConnectTo(*server_); }
  grpc::Status RawBatch(const v1::AlignedSetsRequest& req, v1::AlignedSetsResponse* resp) {
    auto stub = v1::AlignSet::NewStub(
        grpc::CreateChannel(server_->address(), grpc::InsecureChannelCredentials()));
    grpc::ClientContext ctx;
    return stub->GetAlignedSets(&ctx, req, resp);
  }
  ServiceMetrics Metrics() {
    auto m = Client()->GetMetrics();
    EXPECT_TRUE(m.ok());
    return m.ok() ? *m : ServiceMetrics{};
  }

  TempDir dir_;
  std::unique_ptr<ServerProcess> server_;
};

TEST_F(BatchTest, ItemsAreServedInOrderEachWithItsOwnStatus) {
  StartServer(kFast);
  auto client = Client();
  auto batch = client->GetAlignedSets({{128, {30.0}}, {8, {30.0}}, {128, {60.0}},
                                       {128, {10.0, 20.0, 30.0}}, {256, {12.0, 100.0}}});
  ASSERT_TRUE(batch.ok()) << batch.status().message();
  ASSERT_EQ(batch->size(), 5u);
  EXPECT_TRUE((*batch)[0].status.ok()) << (*batch)[0].status.message();
  EXPECT_EQ((*batch)[1].status.code(), Status::Code::kInvalidArgument);
  EXPECT_NE((*batch)[1].status.message().find("below the minimum of 16"), std::string::npos)
      << (*batch)[1].status.message();
  EXPECT_TRUE((*batch)[2].status.ok());
  EXPECT_EQ((*batch)[3].status.code(), Status::Code::kInvalidArgument);
  ASSERT_TRUE((*batch)[4].status.ok()) << (*batch)[4].status.message();
  EXPECT_EQ((*batch)[4].set.points.size(), 256u);
  // 30° and 60° are one canonical set, swapped: one optimization for both.
  ASSERT_EQ((*batch)[2].set.points.size(), 128u);
  for (size_t i = 0; i < 128; ++i) {
    EXPECT_EQ((*batch)[2].set.points[i].x, (*batch)[0].set.points[i].y);
  }
  // The same bytes as the single-set call.
  auto single = client->GetAlignedSet(128, {30.0});
  ASSERT_TRUE(single.ok());
  EXPECT_EQ(single->raw, (*batch)[0].set.raw);
  EXPECT_TRUE(single->info.from_cache);
  EXPECT_EQ(Metrics().optimizations_started, 2u);  // n=128 φ=30, n=256 (12, 100)
}

TEST_F(BatchTest, OneDirectionSpaceIsTheFortySixCanonicalSets) {
  StartServer({"--max-iterations", "20", "--workers", "2", "--threads-per-worker", "1"});
  auto space = Client()->GetOneDirectionSpace(64);
  ASSERT_TRUE(space.ok()) << space.status().message();
  ASSERT_EQ(space->size(), 46u);
  for (int phi = 0; phi < 46; ++phi) {
    const BatchItem& item = (*space)[phi];
    ASSERT_TRUE(item.status.ok()) << phi << ": " << item.status.message();
    EXPECT_EQ(item.set.info.served_deg, std::vector<int>{phi});
    EXPECT_EQ(item.set.info.phi1, phi);
    EXPECT_FALSE(item.set.info.swapped || item.set.info.inverted) << phi;
    EXPECT_EQ(item.set.points.size(), 64u);
  }
  EXPECT_EQ(Metrics().optimizations_completed, 46u);
}

TEST_F(BatchTest, MalformedOrOversizedBatchesAreInvalidArgumentAndTheServerKeepsServing) {
  StartServer({"--max-iterations", "20", "--workers", "1", "--threads-per-worker", "1",
               "--max-n", "1048576"});
  auto expect_invalid = [&](const v1::AlignedSetsRequest& req, const std::string& fragment) {
    v1::AlignedSetsResponse resp;
    const grpc::Status s = RawBatch(req, &resp);
    EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << s.error_message();
    EXPECT_NE(s.error_message().find(fragment), std::string::npos) << s.error_message();
  };
  v1::AlignedSetsRequest req;
  expect_invalid(req, "either items or a space");
  for (int i = 0; i < 257; ++i) {
    auto* item = req.add_items();
    item->set_n(64);
    item->add_directions_deg(i % 46);
  }
  expect_invalid(req, "above the maximum of 256");
  req.set_space(v1::ONE_DIRECTION);
  req.set_space_n(64);
  expect_invalid(req, "either items or a space");
  req.clear_items();
  req.set_space(v1::TWO_DIRECTIONS);
  expect_invalid(req, "only space = ONE_DIRECTION");
  req.set_space(v1::ONE_DIRECTION);
  req.set_space_n(8);
  expect_invalid(req, "below the minimum");
  // 17 sets of 2^20 points: 17.8 million points, above the 2^24 bound; refused
  // before any optimization starts.
  v1::AlignedSetsRequest big;
  for (int i = 0; i < 17; ++i) {
    auto* item = big.add_items();
    item->set_n(1u << 20);
    item->add_directions_deg(i);
  }
  expect_invalid(big, "points in all");
  EXPECT_EQ(Metrics().optimizations_started, 0u);
  auto after = Client()->GetAlignedSet(64, {30.0});
  EXPECT_TRUE(after.ok()) << after.status().message();
}

TEST_F(BatchTest, APerCallDeadlineEndsTheCallAndDropsItsOptimizations) {
  StartServer({"--max-iterations", "100000", "--workers", "2", "--threads-per-worker", "1", "--log-level", "info"});
  auto client = Client();  // no default deadline on the connection
  CallOptions call;
  call.timeout_seconds = 0.3;
  const auto t0 = std::chrono::steady_clock::now();
  auto single = client->GetAlignedSet(2048, {7.0}, call);
  ASSERT_FALSE(single.ok());
  EXPECT_EQ(single.status().code(), Status::Code::kDeadlineExceeded) << single.status().message();
  // A streaming call honours it too (it has no deadline otherwise).
  auto watched = client->WatchAlignedSet(2048, {8.0}, nullptr, call);
  ASSERT_FALSE(watched.ok());
  EXPECT_EQ(watched.status().code(), Status::Code::kDeadlineExceeded);
  auto batch = client->GetAlignedSets({{2048, {9.0}}, {2048, {10.0}}}, call);
  ASSERT_FALSE(batch.ok());
  EXPECT_EQ(batch.status().code(), Status::Code::kDeadlineExceeded) << batch.status().message();
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 10.0);
  // Nobody else wanted those sets: all four optimizations stop, none is stored.
  // Each worker's line comes after the count.
  EXPECT_TRUE(server_->WaitForLog({"optimize cancelled", "withdrawn"}, 4, std::chrono::seconds(10)));
  const ServiceMetrics m = Metrics();
  EXPECT_EQ(m.optimizations_cancelled, 4u);
  EXPECT_EQ(m.optimizations_completed, 0u);
}

}  // namespace
}  // namespace alignset::e2e
