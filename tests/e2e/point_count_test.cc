// One rule for N: the same invalid N is refused in the same words by the
// command line (get, precompute, export, table, optimize), the server (a raw
// request that no command line checked) and the table reader.
#include <gtest/gtest.h>

#include <alignset/client.h>
#include <alignset/set_table.h>

#include <string>
#include <vector>

#include "tests/e2e/e2e_util.h"
#include "tests/e2e/server_process.h"

namespace alignset::e2e {
namespace {

constexpr char kSays[] = "N = 8 is below the minimum of 16 points";

CommandResult Cli(const std::string& args) { return RunCommand(std::string(ALIGNSET_CLI_PATH) + " " + args); }

TEST(PointCountRule, EveryBoundaryRefusesTheSameNInTheSameWords) {
  TempDir dir;
  ServerProcess server(dir.path(), {"--workers", "1", "--threads-per-worker", "1"});
  ASSERT_EQ(server.error(), "");
  const std::string a = server.address(), out = dir.path() + "/x";
  for (const std::string& args :
       {"get --server " + a + " -n 8 --dir 30 --out " + out + ".txt",
        "precompute --server " + a + " -n 8 --space 1dir --construction lattice",
        "export --db " + server.db_path() + " -n 8 -o " + out + ".tbl", "table -n 8 -o " + out + ".tbl",
        "optimize -n 8 --dir 30 --construction lattice -o " + out + ".txt"}) {
    SCOPED_TRACE(args);
    auto r = Cli(args);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(kSays), std::string::npos) << r.output;
  }

  // The server, asked directly (the command line's check bypassed).
  auto client = ConnectTo(server);
  alignset::SetRequest r;
  r.n = 8;
  r.directions_deg = {30.0};
  auto served = client->GetAlignedSet(r);
  ASSERT_FALSE(served.ok());
  EXPECT_EQ(served.status().code(), Status::Code::kInvalidArgument);
  EXPECT_NE(served.status().message().find(kSays), std::string::npos) << served.status().message();

  // The table reader, on a section of 8 points.
  TableSection s;
  s.n = 8;
  s.construction = "lattice";
  s.generators.assign(TableSpaceKeys(TableSpace::kOneDirection), 1);
  auto table = SetTable::FromSections({s});
  ASSERT_FALSE(table.ok());
  EXPECT_NE(table.status().message().find(kSays), std::string::npos) << table.status().message();
}

}  // namespace
}  // namespace alignset::e2e
