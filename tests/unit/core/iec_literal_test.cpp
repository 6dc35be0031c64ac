#include "core/iec_literal.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

namespace virtcom {
namespace {

int64_t integer(std::string_view text) {
  int64_t v = -999;
  EXPECT_TRUE(parseIntegerText(text, v)) << text;
  return v;
}

TEST(IecLiteral, IntegerTextSaturatesAtTheInt64Range) {
  EXPECT_EQ(integer("99999999999999999999"), std::numeric_limits<int64_t>::max());
  EXPECT_EQ(integer("-99999999999999999999"), std::numeric_limits<int64_t>::min());
  EXPECT_EQ(integer("16#FFFF_FFFF"), 0xFFFFFFFF);
  EXPECT_EQ(integer("8#17"), 15);
}

TEST(IecLiteral, IntegerTextWithoutDigitsIsRefused) {
  int64_t v = 0;
  EXPECT_FALSE(parseIntegerText("", v));
  EXPECT_FALSE(parseIntegerText("-", v));
  EXPECT_FALSE(parseIntegerText("16#", v));
  EXPECT_FALSE(parseIntegerText("x1", v));
}

TEST(IecLiteral, TimeTextNeedsTheRightPrefixIfItHasOne) {
  int64_t v = 0;
  EXPECT_TRUE(parseTimeOrDateText("TIME#1h", LiteralFamily::Time, v));
  EXPECT_EQ(v, 3600000);
  EXPECT_TRUE(parseTimeOrDateText("t#-250ms", LiteralFamily::Time, v));
  EXPECT_EQ(v, -250);
  EXPECT_FALSE(parseTimeOrDateText("D#2026-01-01", LiteralFamily::Time, v));
  EXPECT_FALSE(parseTimeOrDateText("T#1s", LiteralFamily::Date, v));
  EXPECT_FALSE(parseTimeOrDateText("TOD#24:00:00", LiteralFamily::Tod, v));
}

TEST(IecLiteral, ErrorsNameWhatIsWrong) {
  uint64_t ns = 0;
  bool negative = false;
  LiteralError why;
  EXPECT_FALSE(decodeDuration("5x", ns, negative, why));
  EXPECT_STREQ(why.what, "unknown unit");
  EXPECT_EQ(why.quoted, "x");
}

}  // namespace
}  // namespace virtcom
