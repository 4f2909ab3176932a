#include "server/log_text.h"

#include <gtest/gtest.h>

namespace alignset::server {
namespace {

TEST(QuotedTest, KeepsPrintableTextAndEscapesTheRest) {
  EXPECT_EQ(Quoted("pmj02bn"), "'pmj02bn'");
  EXPECT_EQ(Quoted("a\nb\rc\td"), "'a\\nb\\rc\\td'");
  EXPECT_EQ(Quoted("it's \\"), "'it\\'s \\\\'");
  EXPECT_EQ(Quoted(std::string("\x00\x7f\xc3\xa9", 4)), "'\\x00\\x7f\\xc3\\xa9'");
}

TEST(QuotedTest, CutsLongTextAndSaysHowLongItWas) {
  const std::string q = Quoted(std::string(1 << 20, 'a'), 8);
  EXPECT_EQ(q, "'aaaaaaaa...' (1048576 bytes)");
  // Escapes count against the output, not the cut: at most 4 bytes each.
  EXPECT_LE(Quoted(std::string(1000, '\n')).size(), 64u * 2 + 32);
  EXPECT_EQ(Quoted(std::string(64, 'b')), "'" + std::string(64, 'b') + "'");
}

}  // namespace
}  // namespace alignset::server
