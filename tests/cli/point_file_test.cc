// Point files in and out (issue 15): every layout a user may hand the CLI is
// read correctly or refused with a clear error, and several sets (UTK's
// '#'-separated text, (m, N, 2) .npy, "set,x,y" CSV) travel both ways.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <alignset/npy.h>

#include "cli/point_file.h"
#include "core/align/canonical.h"
#include "core/sampling/samplers.h"
#include "tests/cli/cli_runner.h"

namespace alignset::cli {
namespace {

using test_support::CliRun;
using test_support::RunCli;

std::string TempPath(const std::string& name) { return test_support::CliTempPath(name); }

std::string Slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A .npy file exactly as numpy.save writes one (format 1.0): the project's
// header (<alignset/npy.h>) for any dtype and order, then `body` as given.
void WriteNpy(const std::string& path, const std::string& descr, const std::vector<size_t>& shape,
              bool fortran, const std::string& body) {
  std::ofstream(path, std::ios::binary) << NpyHeader(shape, fortran, descr) << body;
}

std::string Doubles(const std::vector<double>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double));
}

const PointSet kThree = {{0.125, 0.25}, {0.5, 0.75}, {0.875, 0.0625}};

TEST(PointFileIn, TransposedNpyIsReadAsNPoints) {
  const std::string path = TempPath("t.npy");
  // np.array([xs, ys]): shape (2, 3), the x row first.
  WriteNpy(path, "<f8", {2, 3}, false, Doubles({0.125, 0.5, 0.875, 0.25, 0.75, 0.0625}));
  auto read = ReadPointFile(path);
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(*read, kThree);
  // The same points as a Fortran-order (3, 2) array (np.asfortranarray).
  WriteNpy(path, "<f8", {3, 2}, true, Doubles({0.125, 0.5, 0.875, 0.25, 0.75, 0.0625}));
  read = ReadPointFile(path);
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(*read, kThree);
  // float32 is read too.
  const float f[] = {0.125f, 0.25f, 0.5f, 0.75f, 0.875f, 0.0625f};
  WriteNpy(path, "<f4", {3, 2}, false, std::string(reinterpret_cast<const char*>(f), sizeof(f)));
  read = ReadPointFile(path);
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(*read, kThree);
  std::remove(path.c_str());
}

TEST(PointFileIn, FlatNpyIsAClearError) {
  const std::string path = TempPath("flat.npy");
  WriteNpy(path, "<f8", {6}, false, Doubles({0.125, 0.25, 0.5, 0.75, 0.875, 0.0625}));
  auto read = ReadPointFile(path);
  ASSERT_FALSE(read.ok());
  EXPECT_NE(read.status().message().find("a flat array of 6 values"), std::string::npos)
      << read.status().message();
  EXPECT_NE(read.status().message().find("reshape(-1, 2)"), std::string::npos);
  // And through the CLI: one line, usage status.
  const CliRun r = RunCli("evaluate " + path + " --normal 30");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(test_support::CountLines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("flat array"), std::string::npos) << r.err;
  // Other shapes, a dtype that is not a float, and a short body are refused too.
  for (const auto& [descr, shape, values] :
       std::vector<std::tuple<std::string, std::vector<size_t>, size_t>>{
           {"<f8", {2, 3, 1}, 6}, {"<f8", {3, 3}, 9}, {"<i8", {3, 2}, 6}, {"<f8", {4, 2}, 6}}) {
    WriteNpy(path, descr, shape, false, Doubles(std::vector<double>(values, 0.5)));
    EXPECT_FALSE(ReadPointFile(path).ok()) << descr << " " << NpyShapeText(shape);
  }
  std::remove(path.c_str());
}

// A zero in the shape leaves an empty body, which bounds nothing: the fuzzer's
// (15544708095, 0, 2) once asked for 15 billion empty sets. Every such shape is
// an error naming it, before anything is allocated per set.
TEST(PointFileIn, AShapeWithAZeroIsRefusedBeforeItsOtherDimensionsAreAllocated) {
  const std::string path = TempPath("zero.npy");
  for (const std::vector<size_t>& shape : std::vector<std::vector<size_t>>{
           {15544708095u, 0, 2}, {0, 2}, {2, 0}, {0, 5, 2}, {3, 0, 2}}) {
    WriteNpy(path, "<f8", shape, false, "");
    auto read = ReadPointSets(path);
    ASSERT_FALSE(read.ok()) << NpyShapeText(shape);
    EXPECT_NE(read.status().message().find(NpyShapeText(shape) + " holds no points"), std::string::npos)
        << read.status().message();
  }
  std::remove(path.c_str());
}

TEST(PointFileIn, UtkTextWithSeveralSetsIsSeveralSetsOrAnErrorWhereOneIsExpected) {
  const std::string path = TempPath("multi.txt");
  std::ofstream(path) << "# header\n# another comment line\n0.1 0.2\n0.3 0.4\n#\n0.5 0.6\n"
                         "0.7 0.8\n# set 3\n0.9 0.1\n0.2 0.3\n#\n";
  auto sets = ReadPointSets(path);
  ASSERT_TRUE(sets.ok()) << sets.status().message();
  ASSERT_EQ(sets->size(), 3u);
  EXPECT_EQ((*sets)[1], (PointSet{{0.5, 0.6}, {0.7, 0.8}}));
  auto one = ReadPointFile(path);
  ASSERT_FALSE(one.ok());
  EXPECT_NE(one.status().message().find("holds 3 point sets"), std::string::npos)
      << one.status().message();
  // Where -m applies (variance reads every set): one line per set.
  const CliRun v = RunCli("variance " + path + " --normal 30 --shifts 64");
  ASSERT_EQ(v.exit_code, 0) << v.err;
  EXPECT_EQ(test_support::CountLines(v.out), 4) << v.out;  // header + 3
  EXPECT_NE(v.out.find(path + "[2]\t2\t30\t"), std::string::npos) << v.out;
  // Where one set is expected: a usage error.
  const CliRun e = RunCli("evaluate " + path + " --normal 30");
  EXPECT_EQ(e.exit_code, 2);
  EXPECT_NE(e.err.find("holds 3 point sets"), std::string::npos) << e.err;
  std::remove(path.c_str());
}

TEST(PointFileIn, CoordinatesOutsideTheUnitSquareAreRefused) {
  const std::string txt = TempPath("out.txt"), npy = TempPath("out.npy");
  for (const char* bad : {"1 0.5", "0.5 1.0", "-0.25 0.5", "0.5 1e300"}) {
    std::ofstream(txt) << "0.1 0.2\n" << bad << "\n";
    auto r = ReadPointFile(txt);
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_NE(r.status().message().find("point 1 ("), std::string::npos) << r.status().message();
    EXPECT_NE(r.status().message().find("outside [0, 1)^2"), std::string::npos);
  }
  WriteNpy(npy, "<f8", {2, 2}, false, Doubles({0.1, 0.2, 1.5, 0.5}));
  auto r = ReadPointFile(npy);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("outside [0, 1)^2"), std::string::npos);
  const CliRun c = RunCli("variance " + txt + " --normal 30");
  EXPECT_EQ(c.exit_code, 2);
  EXPECT_NE(c.err.find("outside [0, 1)^2"), std::string::npos) << c.err;
  std::remove(txt.c_str());
  std::remove(npy.c_str());
}

TEST(PointFileOut, CsvIsRealCsvAndReadsBack) {
  const std::string path = TempPath("s.csv");
  const CliRun r = RunCli("sample random -n 16 -s 4 -o " + path);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string text = Slurp(path);
  EXPECT_EQ(text.rfind("x,y\n", 0), 0u) << text;
  EXPECT_EQ(text.find(' '), std::string::npos) << "space-separated: " << text;
  EXPECT_EQ(test_support::CountLines(text), 17);
  EXPECT_EQ(*ReadPointFile(path), *Sample("random", 16, 4));
  // Several sets: a set column.
  ASSERT_EQ(RunCli("sample random -n 16 -s 4 -m 2 -o " + path).exit_code, 0);
  EXPECT_EQ(Slurp(path).rfind("set,x,y\n0,", 0), 0u);
  auto sets = ReadPointSets(path);
  ASSERT_TRUE(sets.ok()) << sets.status().message();
  ASSERT_EQ(sets->size(), 2u);
  EXPECT_EQ((*sets)[1], *Sample("random", 16, 5));
  std::remove(path.c_str());
}

TEST(PointFileOut, DashWritesTheSetToStdoutAndTheReportToStderr) {
  // Run where a file named "-" would land, to see that none does.
  const std::string dir = TempPath("dash");
  std::filesystem::create_directories(dir);
  const std::string cmd = "cd " + dir + " && " + ALIGNSET_CLI_PATH + " sample random -n 16 -s 2 -o -";
  FILE* p = popen((cmd + " 2>" + dir + "/err.txt").c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  char buf[512];
  while (std::fgets(buf, sizeof(buf), p)) out += buf;
  ASSERT_EQ(pclose(p), 0);
  EXPECT_FALSE(std::filesystem::exists(dir + "/-"));
  const std::string text_path = dir + "/from-stdout.txt";
  std::ofstream(text_path) << out;
  EXPECT_EQ(*ReadPointFile(text_path), *Sample("random", 16, 2));
  EXPECT_NE(Slurp(dir + "/err.txt").find("wrote 16 random points to -"),
            std::string::npos);
  // And "-" reads standard input: a pipe from one command into another.
  const CliRun piped = RunCli("sample random -n 16 -s 2 -o - 2>/dev/null | " +
                              std::string(ALIGNSET_CLI_PATH) + " variance - --normal 30 --shifts 64");
  EXPECT_EQ(piped.exit_code, 0) << piped.err;
  EXPECT_NE(piped.out.find("-\t16\t30\t"), std::string::npos) << piped.out;
  std::filesystem::remove_all(dir);
}

TEST(PointFileOut, SeveralSetsAsNpyAndUtkText) {
  const std::string npy = TempPath("m.npy"), txt = TempPath("m.txt");
  ASSERT_EQ(RunCli("sample owen-sobol -n 32 -s 7 -m 3 -o " + npy).exit_code, 0);
  const std::string data = Slurp(npy);
  EXPECT_NE(data.find("'shape': (3, 32, 2)"), std::string::npos);
  ASSERT_EQ(RunCli("sample owen-sobol -n 32 -s 7 -m 3 -o " + txt).exit_code, 0);
  for (const std::string& path : {npy, txt}) {
    auto sets = ReadPointSets(path);
    ASSERT_TRUE(sets.ok()) << sets.status().message();
    ASSERT_EQ(sets->size(), 3u) << path;
    for (int i = 0; i < 3; ++i) EXPECT_EQ((*sets)[i], *Sample("owen-sobol", 32, 7 + i)) << path;
  }
  // (m, N, 2) with m = 1 is one set; sets of different sizes cannot be one array.
  ASSERT_TRUE(WritePointSets(npy, {kThree}).ok());
  EXPECT_NE(Slurp(npy).find("'shape': (1, 3, 2)"), std::string::npos);
  EXPECT_EQ(*ReadPointFile(npy), kThree);
  EXPECT_FALSE(WritePointSets(npy, {kThree, {{0.5, 0.5}}}).ok());
  EXPECT_TRUE(WritePointSets(txt, {kThree, {{0.5, 0.5}}}).ok());
  // optimize -m: set i is the set of seed S + i.
  const std::string one = TempPath("one.txt");
  ASSERT_EQ(RunCli("optimize -n 64 --dir 30 -s 5 -m 2 --max-iterations 20 -o " + txt).exit_code, 0);
  ASSERT_EQ(RunCli("optimize -n 64 --dir 30 -s 6 --max-iterations 20 -o " + one).exit_code, 0);
  auto sets = ReadPointSets(txt);
  ASSERT_TRUE(sets.ok());
  ASSERT_EQ(sets->size(), 2u);
  EXPECT_EQ((*sets)[1], *ReadPointFile(one));
  EXPECT_NE((*sets)[0], (*sets)[1]);
  // align keeps every set.
  ASSERT_EQ(RunCli("align " + txt + " --canonical 30 --dir 120 -o " + npy).exit_code, 0);
  auto aligned = ReadPointSets(npy);
  ASSERT_TRUE(aligned.ok());
  ASSERT_EQ(aligned->size(), 2u);
  EXPECT_EQ((*aligned)[1], Align((*sets)[1], {true, true, false}));
  for (const std::string& p : {npy, txt, one}) std::remove(p.c_str());
}

// A device or a pipe given as the output (`-o /dev/null`) is written into,
// not replaced: the atomic write renames a temporary file onto the path,
// which as root turned /dev/null into a regular file. A FIFO stands in for
// the device: it must still be a FIFO afterwards and carry the bytes. Also
// through WriteNpy, the public .npy writer.
TEST(PointFileOut, AFifoIsWrittenIntoNotReplaced) {
  for (const std::string name : {"out.csv", "out.npy", "raw.npy"}) {
    const std::string fifo = TempPath(name);
    std::remove(fifo.c_str());
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
    // Open for reading first (non-blocking), so the writer's open succeeds.
    const int reader = open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
    ASSERT_GE(reader, 0) << std::strerror(errno);
    const Status written = name == "raw.npy" ? alignset::WriteNpy(fifo, std::vector<size_t>{3, 2},
                                                        std::vector<double>{0.1, 0.2, 0.3, 0.4, 0.5, 0.6})
                                             : WritePointFile(fifo, kThree);
    EXPECT_TRUE(written.ok()) << written.message();
    struct stat st;
    ASSERT_EQ(stat(fifo.c_str(), &st), 0);
    EXPECT_TRUE(S_ISFIFO(st.st_mode)) << name << " was replaced";
    char buffer[4096];
    const ssize_t got = read(reader, buffer, sizeof buffer);
    EXPECT_GT(got, 0) << name << ": nothing came through the pipe";
    if (got > 0 && name != "out.csv") {
      EXPECT_EQ(std::string(buffer, 6), "\x93NUMPY") << name;
    }
    close(reader);
    std::remove(fifo.c_str());
  }
}

}  // namespace
}  // namespace alignset::cli
