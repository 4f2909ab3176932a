#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/point_file.h"
#include "tests/cli/cli_runner.h"
#include "core/align/canonical.h"
#include "core/sampling/samplers.h"
#include "core/sampling/shear.h"

namespace alignset::cli {
namespace {

using test_support::CliRun;

std::string TempPath(const std::string& name) { return test_support::CliTempPath(name); }

CliRun Cli(const std::string& args) { return test_support::RunCli(args); }

int Lines(const std::string& s) { return test_support::CountLines(s); }

TEST(SampleCli, WritesTheRegistrysSetAndShears) {
  const std::string out = TempPath("p.txt");
  ASSERT_EQ(Cli("sample pmj02bn --n 256 --seed 4 --out " + out).exit_code, 0);
  auto read = ReadPointFile(out);
  ASSERT_TRUE(read.ok());
  EXPECT_EQ(*read, *Sample("pmj02bn", 256, 4));  // %.17g round-trips doubles
  ASSERT_EQ(Cli("sample pmj02bn --n 256 --seed 4 --shear 25 --out " + out).exit_code, 0);
  EXPECT_EQ(*ReadPointFile(out), Shear(*Sample("pmj02bn", 256, 4), 25));
  std::remove(out.c_str());
}

TEST(SampleCli, BadInputIsOneLineAndNonZero) {
  const std::string out = TempPath("bad.txt");
  for (const std::string& args : std::vector<std::string>
       {"sample jittered --n 1000 --out " + out, "sample nope --n 16 --out " + out,
        "sample random --n 0 --out " + out, std::string("sample random --n 16"), "sample --n 16 --out " + out,
        "sample random --n 16 --shear inf --out " + out, "sample random --n abc --out " + out}) {
    const CliRun r = Cli(args);
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_EQ(Lines(r.err), 1) << args << ": " << r.err;
  }
  EXPECT_NE(Cli("sample jittered --n 1000 --out " + out).err.find("961 or 1024"), std::string::npos);
}

TEST(AlignCli, AlignsFromTheMatchingKeyOnly) {
  const std::string in = TempPath("in.txt"), out = TempPath("out.txt");
  const PointSet p = *Sample("owen-sobol", 64, 1);
  ASSERT_TRUE(WritePointFile(in, p).ok());
  ASSERT_EQ(Cli("align " + in + " --canonical 30 --dir 120 --out " + out).exit_code, 0);
  EXPECT_EQ(*ReadPointFile(out), Align(p, {true, true, false}));
  const CliRun wrong = Cli("align " + in + " --canonical 20 --dir 120 --out " + out);
  EXPECT_NE(wrong.exit_code, 0);
  EXPECT_EQ(Lines(wrong.err), 1);
  std::remove(in.c_str());
  std::remove(out.c_str());
}

}  // namespace
}  // namespace alignset::cli
