// `alignset export` against a real server's cache: the table's set for any
// direction is the set the server serves for it, and what the table lacks
// is named.
#include <gtest/gtest.h>

#include <alignset/client.h>
#include <alignset/set_table.h>

#include <string>
#include <vector>

#include "tests/e2e/e2e_util.h"
#include "tests/e2e/server_process.h"

namespace alignset::e2e {
namespace {

const std::vector<std::string> kFlags = {"--max-iterations", "40", "--workers", "2", "--threads-per-worker", "1",
                                         "--max-n", "4096"};

class ExportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    server_ = std::make_unique<ServerProcess>(dir_.path(), kFlags);
    ASSERT_EQ(server_->error(), "");
  }
  CommandResult Cli(const std::string& args) { return RunCommand(std::string(ALIGNSET_CLI_PATH) + " " + args); }
  TempDir dir_;
  std::unique_ptr<ServerProcess> server_;
};

TEST_F(ExportTest, TheTablesSetForEveryDirectionIsTheServersSet) {
  const std::string a = server_->address();
  for (const char* c : {"lattice", "tent-lattice", "optimized"}) {
    auto pre = Cli("precompute --server " + a + " -n 64 --space 1dir --construction " + c);
    ASSERT_EQ(pre.exit_code, 0) << pre.output;
  }
  auto pairs = Cli("precompute --server " + a + " -n 64 --space keys --key 10,100 --key 12,77 --construction lattice");
  ASSERT_EQ(pairs.exit_code, 0) << pairs.output;
  // The optimized sets are keyed by the server's settings (the harness runs
  // it with its own): the export names them by the profile the server reports.
  auto probe = ConnectTo(*server_)->GetAlignedSet(64, {30.0});
  ASSERT_TRUE(probe.ok()) << probe.status().message();
  const std::string table_path = dir_.path() + "/sets.tbl";
  auto wrong = Cli("export --db " + server_->db_path() + " -n 64 --construction optimized -o " + table_path);
  EXPECT_EQ(wrong.exit_code, 1);
  EXPECT_NE(wrong.output.find("give --profile"), std::string::npos) << wrong.output;
  auto ex = Cli("export --db " + server_->db_path() + " -n 64 --construction lattice,tent-lattice,optimized --profile " +
                probe->info.profile + " -o " + table_path);
  ASSERT_EQ(ex.exit_code, 0) << ex.output;
  EXPECT_NE(ex.output.find("sections       3"), std::string::npos) << ex.output;
  auto table = SetTable::Load(table_path);
  ASSERT_TRUE(table.ok()) << table.status().message();

  auto client = ConnectTo(*server_);
  for (int deg : {0, 17, 45, 63, 90, 122, 150, 179}) {
    SCOPED_TRACE(deg);
    for (const char* c : {"lattice", "tent-lattice"}) {
      alignset::SetRequest r;
      r.n = 64;
      r.directions_deg = {static_cast<double>(deg)};
      r.construction = c;
      auto served = client->GetAlignedSet(r);
      ASSERT_TRUE(served.ok()) << served.status().message();
      auto set = (*table)->Find(64, c, {SetChoice::Kind::kOne, deg, 0});
      ASSERT_TRUE(set.ok()) << set.status().message();
      EXPECT_EQ(set->lattice_generator, served->info.lattice_generator) << c;
      EXPECT_EQ(set->folded, std::string(c) == "tent-lattice");
    }
    alignset::SetRequest r;
    r.n = 64;
    r.directions_deg = {static_cast<double>(deg)};
    r.steps_per_degree = 1;
    auto served = client->GetAlignedSet(r);
    ASSERT_TRUE(served.ok()) << served.status().message();
    auto set = (*table)->Find(64, "optimized", {SetChoice::Kind::kOne, deg, 0});
    ASSERT_TRUE(set.ok());
    EXPECT_EQ(*set->points, served->points);  // bit for bit
  }

  // A table with only the pairs a scene needs is refused: a space is whole
  // or absent, and the message says what to precompute.
  auto missing = Cli("export --db " + server_->db_path() + " -n 64 --space 2dir -o " + dir_.path() + "/two.tbl");
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_NE(missing.output.find("4139 of 4141 keys are not in the cache"), std::string::npos) << missing.output;
  EXPECT_NE(missing.output.find("alignset precompute --n 64 --space 2dir --construction lattice"), std::string::npos);
  auto bad = Cli("export --db " + server_->db_path() + " -n 64 --space 3dir -o " + dir_.path() + "/x.tbl");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  auto no_db = Cli("export --db " + dir_.path() + "/none.sqlite -n 64 -o " + dir_.path() + "/x.tbl");
  EXPECT_EQ(no_db.exit_code, 2) << no_db.output;
}

}  // namespace
}  // namespace alignset::e2e
