#include "core/ascii.hpp"

#include <gtest/gtest.h>

namespace virtcom {
namespace {

TEST(Ascii, FoldsOnlyAsciiLetters) {
  EXPECT_EQ(asciiUpper("abc_XYZ-09"), "ABC_XYZ-09");
  EXPECT_EQ(asciiLower("ABC_xyz-09"), "abc_xyz-09");
  EXPECT_EQ(asciiUpper("\xE4\xC4"), "\xE4\xC4");  // Latin-1 bytes are not letters here
  EXPECT_EQ(asciiUpper('@'), '@');
  EXPECT_EQ(asciiUpper('['), '[');
  EXPECT_EQ(asciiLower('`'), '`');
}

TEST(Ascii, ComparesWithoutCase) {
  EXPECT_TRUE(iequalsAscii("Main.Count", "MAIN.count"));
  EXPECT_TRUE(iequalsAscii("", ""));
  EXPECT_FALSE(iequalsAscii("MAIN", "MAINX"));
  EXPECT_FALSE(iequalsAscii("a_", "A-"));
  EXPECT_FALSE(iequalsAscii("@", "`"));  // 0x40 and 0x60 differ by the case bit but are no letters
  EXPECT_TRUE(istartsWithAscii("Attribute 'x'", "attribute"));
  EXPECT_FALSE(istartsWithAscii("attr", "attribute"));
  EXPECT_TRUE(iendsWithAscii("plc/Main.TcPOU", ".tcpou"));
  EXPECT_TRUE(iendsWithAscii("project.XML", ".xml"));
  EXPECT_FALSE(iendsWithAscii("xml", ".xml"));
}

TEST(Ascii, DigitValuesUpToBase36) {
  EXPECT_EQ(asciiDigitValue('0'), 0);
  EXPECT_EQ(asciiDigitValue('9'), 9);
  EXPECT_EQ(asciiDigitValue('a'), 10);
  EXPECT_EQ(asciiDigitValue('F'), 15);
  EXPECT_EQ(asciiDigitValue('z'), 35);
  EXPECT_EQ(asciiDigitValue('_'), -1);
  EXPECT_EQ(asciiDigitValue(' '), -1);
  static_assert(iequalsAscii("ms", "MS") && asciiDigitValue('Z') == 35, "usable at compile time");
}

}  // namespace
}  // namespace virtcom
