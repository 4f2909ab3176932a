#include "storage/paths.h"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <optional>

#include "tests/storage/test_util.h"

namespace alignset::storage {
namespace {

// Sets or unsets an environment variable for one test, restoring it after.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = getenv(name)) old_ = old;
    if (value) setenv(name, value, 1);
    else unsetenv(name);
  }
  ~ScopedEnv() {
    if (old_) setenv(name_, old_->c_str(), 1);
    else unsetenv(name_);
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(DefaultDatabasePath, AlignsetDataDirWins) {
  testing::TempDir dir;
  const std::string data = dir.File("data/deeper");
  ScopedEnv a("ALIGNSET_DATA_DIR", data.c_str());
  ScopedEnv x("XDG_DATA_HOME", dir.File("xdg").c_str());
  auto p = DefaultDatabasePath();
  ASSERT_TRUE(p.ok()) << p.status().ToString();
  EXPECT_EQ(*p, data + "/alignset.sqlite");
  EXPECT_TRUE(std::filesystem::is_directory(data));
}

TEST(DefaultDatabasePath, XdgDataHomeThenHome) {
  testing::TempDir dir;
  ScopedEnv a("ALIGNSET_DATA_DIR", nullptr);
  ScopedEnv h("HOME", dir.File("home").c_str());
  {
    ScopedEnv x("XDG_DATA_HOME", dir.File("xdg").c_str());
    EXPECT_EQ(*DefaultDatabasePath(), dir.File("xdg") + "/alignset/alignset.sqlite");
  }
  {
    ScopedEnv x("XDG_DATA_HOME", "relative/is/ignored");
    EXPECT_EQ(*DefaultDatabasePath(), dir.File("home") + "/.local/share/alignset/alignset.sqlite");
  }
  ScopedEnv x("XDG_DATA_HOME", nullptr);
  auto p = DefaultDatabasePath();
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(*p, dir.File("home") + "/.local/share/alignset/alignset.sqlite");
  EXPECT_TRUE(std::filesystem::is_directory(dir.File("home") + "/.local/share/alignset"));
}

TEST(DefaultDatabasePath, NoDirectoryAtAllIsAnError) {
  ScopedEnv a("ALIGNSET_DATA_DIR", nullptr);
  ScopedEnv x("XDG_DATA_HOME", nullptr);
  ScopedEnv h("HOME", nullptr);
  EXPECT_EQ(DefaultDatabasePath().status().code(), Status::Code::kInvalidArgument);
}

TEST(DefaultDatabasePath, UncreatableDirectoryIsAnError) {
  testing::TempDir dir;
  const std::string file = dir.File("plainfile");
  { std::ofstream(file) << "x"; }
  ScopedEnv a("ALIGNSET_DATA_DIR", (file + "/sub").c_str());
  EXPECT_FALSE(DefaultDatabasePath().ok());
}

}  // namespace
}  // namespace alignset::storage
