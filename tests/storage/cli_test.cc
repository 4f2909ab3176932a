// `alignset cache ...` end to end, through the real binary.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "storage/set_cache.h"
#include "tests/storage/test_util.h"

namespace alignset::storage {
namespace {

using testing::Key1;
using testing::Key2;
using testing::MakeRecord;
using testing::RawDb;
using testing::TempDir;

struct CliRun {
  int rc = -1;
  std::string out;  // stdout and stderr
};

CliRun Cli(const std::string& args) {
  CliRun r;
  const std::string cmd = std::string(ALIGNSET_CLI_PATH) + " cache " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (p == nullptr) return r;
  char buf[4096];
  size_t got;
  while ((got = fread(buf, 1, sizeof(buf), p)) > 0) r.out.append(buf, got);
  const int status = pclose(p);
  r.rc = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

void WriteShard(const std::string& path, const std::vector<SetKey>& keys) {
  auto c = SetCache::Open(path);
  ASSERT_TRUE(c.ok());
  for (const SetKey& k : keys) ASSERT_TRUE((*c)->Put(MakeRecord(k, 1)).ok());
}

int64_t Count(const std::string& path) {
  auto c = SetCache::Open(path);
  return c.ok() ? (*c)->Stats()->sets : -1;
}

TEST(CacheCli, MergeVerifyListExportImport) {
  TempDir dir;
  const std::string a = dir.File("a.sqlite"), b = dir.File("b.sqlite"), m = dir.File("m.sqlite");
  WriteShard(a, {Key1(64, 0), Key1(64, 1), Key2(128, 2, 3)});
  WriteShard(b, {Key1(64, 1), Key1(256, 40)});

  CliRun r = Cli("merge --out " + m + " " + a + " " + b);
  ASSERT_EQ(r.rc, 0) << r.out;
  EXPECT_EQ(Count(m), 4);
  EXPECT_FALSE(std::filesystem::exists(m + ".partial"));
  EXPECT_EQ(Cli("merge --out " + m + " " + a).rc, 2);  // refuses to overwrite

  r = Cli("verify --db " + m);
  EXPECT_EQ(r.rc, 0) << r.out;
  EXPECT_NE(r.out.find("checked 4 sets: 4 readable, 0 damaged; no damage found"), std::string::npos) << r.out;

  r = Cli("list --db " + m);
  EXPECT_EQ(r.rc, 0) << r.out;
  EXPECT_NE(r.out.find("4 listed; the file holds 4 sets (3 one-direction, 1 two-direction)"),
            std::string::npos) << r.out;
  r = Cli("list --db " + m + " --n 64");
  EXPECT_EQ(r.rc, 0);
  EXPECT_NE(r.out.find("2 listed; the file holds 4 sets"), std::string::npos) << r.out;

  const std::string e = dir.File("e.sqlite");
  r = Cli("export --db " + m + " --out " + e);
  EXPECT_EQ(r.rc, 0) << r.out;
  EXPECT_EQ(Count(e), 4);
  EXPECT_EQ(Cli("export --db " + m + " --out " + e).rc, 2);

  const std::string c = dir.File("c.sqlite");
  WriteShard(c, {Key1(512, 9), Key1(64, 0)});
  r = Cli("import --db " + e + " " + c);
  EXPECT_EQ(r.rc, 0) << r.out;
  EXPECT_NE(r.out.find("added 1, already present 1, damaged (skipped) 0"), std::string::npos) << r.out;
  EXPECT_EQ(Count(e), 5);
}

TEST(CacheCli, DamageIsReportedWithExitStatusOne) {
  TempDir dir;
  const std::string a = dir.File("a.sqlite");
  WriteShard(a, {Key1(64, 0), Key1(64, 1)});
  {
    RawDb raw(a);
    ASSERT_TRUE(raw.FlipBlobByte(Key1(64, 1), 17));
  }
  CliRun r = Cli("verify --db " + a);
  EXPECT_EQ(r.rc, 1) << r.out;
  EXPECT_NE(r.out.find("DAMAGED n=64 dirs=1:1"), std::string::npos) << r.out;
  r = Cli("merge --out " + dir.File("m.sqlite") + " " + a);
  EXPECT_EQ(r.rc, 1) << r.out;
  EXPECT_EQ(Count(dir.File("m.sqlite")), 1);
}

// OUT.partial may be another merge's work in progress (issue 16, smaller
// things): refused unless --force.
TEST(CacheCli, MergeLeavesAnExistingPartialFileAloneUnlessForced) {
  TempDir dir;
  const std::string a = dir.File("a.sqlite");
  WriteShard(a, {Key1(64, 0), Key1(64, 1)});
  const std::string out = dir.File("m.sqlite");
  { std::ofstream(out + ".partial") << "another merge's work"; }
  CliRun r = Cli("merge --out " + out + " " + a);
  EXPECT_EQ(r.rc, 2) << r.out;
  EXPECT_NE(r.out.find("--force"), std::string::npos) << r.out;
  std::ifstream partial(out + ".partial");
  std::string kept((std::istreambuf_iterator<char>(partial)), std::istreambuf_iterator<char>());
  EXPECT_EQ(kept, "another merge's work");
  EXPECT_FALSE(std::filesystem::exists(out));
  r = Cli("merge --force --out " + out + " " + a);
  EXPECT_EQ(r.rc, 0) << r.out;
  EXPECT_EQ(Count(out), 2);
  EXPECT_FALSE(std::filesystem::exists(out + ".partial"));
}

// Exit 0 when the files agree, 1 when they differ, as diff(1); keys one file
// lacks count unless --shared-only.
TEST(CacheCli, DiffComparesTheSharedSetsBitForBit) {
  TempDir dir;
  const std::string a = dir.File("a.sqlite"), b = dir.File("b.sqlite");
  WriteShard(a, {Key1(64, 0), Key1(64, 1), Key2(128, 2, 3)});
  WriteShard(b, {Key1(64, 0), Key1(64, 1)});
  CliRun r = Cli("diff " + a + " " + b);
  EXPECT_EQ(r.rc, 1) << r.out;
  EXPECT_NE(r.out.find("ONLY " + a + " n=128 dirs=2:2,3"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("compared 2 shared sets: 2 the same, 0 differ, 0 damaged; 1 only in " + a +
                       ", 0 only in " + b + "; the files differ"),
            std::string::npos) << r.out;
  r = Cli("diff --shared-only " + a + " " + b);
  EXPECT_EQ(r.rc, 0) << r.out;
  EXPECT_EQ(r.out.find("ONLY "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("the files agree"), std::string::npos) << r.out;
  EXPECT_EQ(Cli("diff -n 64 " + a + " " + b).rc, 0);

  {  // another fill of one key, its last point moved
    auto cache = SetCache::Open(b);
    ASSERT_TRUE(cache.ok());
    SetRecord rec = MakeRecord(Key1(64, 1), 1);
    rec.points.back().x = 0.5 * rec.points.back().x;
    ASSERT_TRUE((*cache)->Put(rec).ok());
  }
  r = Cli("diff --shared-only " + b + " " + a);
  EXPECT_EQ(r.rc, 1) << r.out;
  EXPECT_NE(r.out.find("DIFFERS n=64 dirs=1:1 profile=0123456789abcdef: 1 of 64 points"),
            std::string::npos) << r.out;
  {
    RawDb raw(a);
    ASSERT_TRUE(raw.FlipBlobByte(Key1(64, 0), 17));
  }
  r = Cli("diff --shared-only " + b + " " + a);
  EXPECT_EQ(r.rc, 1) << r.out;
  EXPECT_NE(r.out.find("DAMAGED n=64 dirs=1:0 profile=0123456789abcdef in " + a), std::string::npos)
      << r.out;
  EXPECT_EQ(Cli("diff " + a).rc, 2);
  EXPECT_EQ(Cli("diff " + a + " " + dir.File("missing.sqlite")).rc, 2);
  EXPECT_FALSE(std::filesystem::exists(dir.File("missing.sqlite")));
}

TEST(CacheCli, UsageErrorsExitTwo) {
  TempDir dir;
  EXPECT_EQ(Cli("").rc, 2);
  EXPECT_EQ(Cli("frobnicate").rc, 2);
  EXPECT_EQ(Cli("verify").rc, 2);
  EXPECT_EQ(Cli("verify --db " + dir.File("missing.sqlite")).rc, 2);
  EXPECT_FALSE(std::filesystem::exists(dir.File("missing.sqlite")));
  EXPECT_EQ(Cli("import --db " + dir.File("x.sqlite")).rc, 2);
  EXPECT_EQ(Cli("import --db " + dir.File("x.sqlite") + " " + dir.File("nope")).rc, 2);
  EXPECT_EQ(Cli("list --db " + dir.File("x.sqlite") + " --bogus 1").rc, 2);
  EXPECT_EQ(Cli("help").rc, 0);
}

}  // namespace
}  // namespace alignset::storage
