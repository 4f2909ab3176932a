// `alignset table` (lattices searched by the command line, no server) against
// `alignset export` of a real server's cache: the same file, byte for byte,
// because both run the same core search for every key.
#include <gtest/gtest.h>

#include <string>

#include "tests/e2e/e2e_util.h"
#include "tests/e2e/server_process.h"

namespace alignset::e2e {
namespace {

CommandResult Cli(const std::string& args) { return RunCommand(std::string(ALIGNSET_CLI_PATH) + " " + args); }

TEST(TableTest, ALatticeTableWithoutAServerIsTheExportedTable) {
  TempDir dir;
  ServerProcess server(dir.path(), {"--workers", "2", "--threads-per-worker", "1", "--max-n", "4096"});
  ASSERT_EQ(server.error(), "");
  const std::string a = server.address();
  for (const char* space : {"1dir", "1dir-quarter"}) {
    SCOPED_TRACE(space);
    const std::string step = std::string(space) == "1dir" ? "" : " --angle-step 0.25";
    auto pre = Cli("precompute --server " + a + " -n 48,192,768 --space 1dir" + step + " --construction lattice");
    ASSERT_EQ(pre.exit_code, 0) << pre.output;
    const std::string exported = dir.path() + "/exported-" + space + ".tbl";
    const std::string direct = dir.path() + "/direct-" + space + ".tbl";
    auto ex = Cli("export --db " + server.db_path() + " -n 48,192,768 --construction lattice --space " + space +
                  " -o " + exported);
    ASSERT_EQ(ex.exit_code, 0) << ex.output;
    auto made = Cli("table -n 48,192,768 --construction lattice --space " + std::string(space) + " -o " + direct);
    ASSERT_EQ(made.exit_code, 0) << made.output;
    EXPECT_NE(made.output.find("sections       3"), std::string::npos) << made.output;
    const std::string want = ReadText(exported), got = ReadText(direct);
    ASSERT_GT(want.size(), 0u);
    EXPECT_TRUE(got == want) << "alignset table wrote " << got.size() << " bytes that differ from export's "
                             << want.size();
  }
  // A net (points, not a generator) the same way.
  auto pre = Cli("precompute --server " + a + " -n 64 --space 1dir --construction net");
  ASSERT_EQ(pre.exit_code, 0) << pre.output;
  auto ex = Cli("export --db " + server.db_path() + " -n 64 --construction net -o " + dir.path() + "/net-e.tbl");
  ASSERT_EQ(ex.exit_code, 0) << ex.output;
  auto made = Cli("table -n 64 --construction net -o " + dir.path() + "/net-t.tbl");
  ASSERT_EQ(made.exit_code, 0) << made.output;
  EXPECT_TRUE(ReadText(dir.path() + "/net-t.tbl") == ReadText(dir.path() + "/net-e.tbl"));
}

TEST(TableTest, WhatTheServerMakesIsRefusedWithWhereToGetIt) {
  TempDir dir;
  auto opt = Cli("table -n 256 --construction optimized -o " + dir.path() + "/t.tbl");
  EXPECT_EQ(opt.exit_code, 2);
  EXPECT_NE(opt.output.find("alignset export --construction optimized"), std::string::npos) << opt.output;
  auto net = Cli("table -n 48 --construction lattice-sequence,net -o " + dir.path() + "/t.tbl");
  EXPECT_EQ(net.exit_code, 2) << net.output;  // a net's N is a power of two
  EXPECT_NE(net.output.find("construction 'net' needs N a power of two"), std::string::npos) << net.output;
  auto space = Cli("table -n 48 --space 3dir -o " + dir.path() + "/t.tbl");
  EXPECT_EQ(space.exit_code, 2);
  EXPECT_NE(space.output.find("'3dir' is not 1dir, 1dir-quarter or 2dir"), std::string::npos) << space.output;
}

}  // namespace
}  // namespace alignset::e2e
