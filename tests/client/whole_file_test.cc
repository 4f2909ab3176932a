// The whole-file writer the point files and .npy files share
// (client/whole_file.h): a replaced file is never seen half-written, a
// failed write says which path and why and leaves no temporary behind.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "client/whole_file.h"
#include "tests/cli/cli_runner.h"

namespace alignset {
namespace {

namespace fs = std::filesystem;

std::string Slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// Every entry of `dir` whose name starts with `stem` and is not `stem`
// itself: a temporary left behind.
int Strays(const fs::path& dir, const std::string& stem) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name != stem && name.rfind(stem, 0) == 0) ++n;
  }
  return n;
}

TEST(WholeFile, ReplacesAFileWholeAndLeavesNoTemporary) {
  const fs::path dir = test_support::CliTempPath("whole_file_dir");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string path = (dir / "points.txt").string();
  ASSERT_TRUE(WriteWholeFile(path, "first version, longer than the second\n").ok());
  ASSERT_TRUE(WriteWholeFile(path, std::string("second\0binary", 13)).ok());
  EXPECT_EQ(Slurp(path), std::string("second\0binary", 13));  // no tail of the first left
  EXPECT_EQ(Strays(dir, "points.txt"), 0);
  fs::remove_all(dir);
}

TEST(WholeFile, AFailedWriteNamesThePathAndLeavesNothing) {
  const fs::path dir = test_support::CliTempPath("whole_file_fail");
  fs::remove_all(dir);
  fs::create_directories(dir / "a_folder");
  // Into a folder that does not exist: the temporary cannot be made.
  const std::string missing = (dir / "no_such_folder" / "out.npy").string();
  const Status s = WriteWholeFile(missing, "x");
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.code(), Status::Code::kInvalidArgument);
  EXPECT_NE(s.message().find(missing), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("No such file"), std::string::npos) << s.message();
  // Onto a folder (not a regular file, so written into, as a device is):
  // refused, the folder untouched, nothing left beside it.
  const std::string folder = (dir / "a_folder").string();
  const Status onto = WriteWholeFile(folder, "x");
  ASSERT_FALSE(onto.ok());
  EXPECT_NE(onto.message().find(folder), std::string::npos) << onto.message();
  EXPECT_TRUE(fs::is_directory(folder));
  EXPECT_EQ(Strays(dir, "a_folder"), 0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace alignset
