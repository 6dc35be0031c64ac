// Every spelling the ST lexer and bytecode's value parser (--set, cell wiring) read through
// core/iec_literal, pinned at the reader itself: a change here changes both callers at once.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>

#include "core/ascii.hpp"
#include "core/duration_units.hpp"
#include "core/iec_literal.hpp"
#include "core/iec_value.hpp"

namespace virtcom {
namespace {

// The signed nanoseconds of a duration body, or the reader's complaint.
std::string duration(std::string_view body) {
  uint64_t ns = 0;
  bool negative = false;
  LiteralError why;
  if (!decodeDuration(body, ns, negative, why)) return std::string("error: ") + why.what;
  std::string text(negative ? "-" : "");
  text += std::to_string(ns);  // appended: `"-" + to_string` trips GCC 12's -Wrestrict
  return text;
}

std::string body(std::string_view text, LiteralFamily family) {
  int64_t value = 0;
  LiteralError why;
  if (!decodeLiteralBody(text, family, value, why)) return std::string("error: ") + why.what;
  return std::to_string(value);
}

TEST(LiteralSyntax, EveryPrefixSpellingInAnyCase) {
  struct Case {
    const char* prefix;
    LiteralFamily family;
  };
  for (Case c : {Case{"T", LiteralFamily::Time}, {"TIME", LiteralFamily::Time}, {"t", LiteralFamily::Time},
                 {"time", LiteralFamily::Time}, {"LT", LiteralFamily::Ltime}, {"LTIME", LiteralFamily::Ltime},
                 {"ltime", LiteralFamily::Ltime}, {"D", LiteralFamily::Date}, {"DATE", LiteralFamily::Date},
                 {"d", LiteralFamily::Date}, {"TOD", LiteralFamily::Tod}, {"TIME_OF_DAY", LiteralFamily::Tod},
                 {"Tod", LiteralFamily::Tod}, {"DT", LiteralFamily::Dt}, {"DATE_AND_TIME", LiteralFamily::Dt},
                 {"date_and_time", LiteralFamily::Dt}, {"INT", LiteralFamily::None}, {"Color", LiteralFamily::None},
                 {"", LiteralFamily::None}, {"TI", LiteralFamily::None}, {"16", LiteralFamily::None}})
    EXPECT_EQ(literalFamily(c.prefix), c.family) << c.prefix;
}

TEST(LiteralSyntax, DurationUnitsInAnyCase) {
  EXPECT_EQ(duration("1d"), "86400000000000");
  EXPECT_EQ(duration("1h"), "3600000000000");
  EXPECT_EQ(duration("1m"), "60000000000");
  EXPECT_EQ(duration("1s"), "1000000000");
  EXPECT_EQ(duration("1ms"), "1000000");
  EXPECT_EQ(duration("1us"), "1000");
  EXPECT_EQ(duration("1ns"), "1");
  EXPECT_EQ(duration("1D2H3M4S5MS6US7NS"), duration("1d2h3m4s5ms6us7ns"));
  EXPECT_EQ(duration("1Ms"), "1000000");
  EXPECT_EQ(duration("1m30s"), "90000000000");  // m is minutes, ms milliseconds
  EXPECT_EQ(duration("30ms"), "30000000");
}

TEST(LiteralSyntax, DurationSignsFractionsAndUnderscores) {
  EXPECT_EQ(duration("-2m"), "-120000000000");
  EXPECT_EQ(duration("+1s"), "1000000000");
  EXPECT_EQ(duration("1.5h"), "5400000000000");
  EXPECT_EQ(duration("1.5us"), "1500");
  EXPECT_EQ(duration("0.5ns"), "1");  // fractions round to the nearest nanosecond
  EXPECT_EQ(duration("1.s"), "1000000000");
  EXPECT_EQ(duration("1_000ms"), "1000000000");
  EXPECT_EQ(duration("1d_2h"), "93600000000000");
  EXPECT_EQ(duration("1ms__2us"), "1002000");
  EXPECT_EQ(duration("_1ms"), "1000000");
  EXPECT_EQ(duration("1_ms"), "1000000");
}

TEST(LiteralSyntax, DurationRefusalsSayWhy) {
  EXPECT_EQ(duration(""), "error: no value");
  EXPECT_EQ(duration("-"), "error: no value");
  EXPECT_EQ(duration("5"), "error: missing unit (d, h, m, s, ms, us, ns)");
  EXPECT_EQ(duration("5x"), "error: unknown unit");
  EXPECT_EQ(duration("5min"), "error: unknown unit");  // min is a cell-file unit, not IEC
  EXPECT_EQ(duration(".5s"), "error: expected a number");
  EXPECT_EQ(duration("1.5_0s"), "error: missing unit (d, h, m, s, ms, us, ns)");
  EXPECT_EQ(duration("1.5.5s"), "error: missing unit (d, h, m, s, ms, us, ns)");
  EXPECT_EQ(duration("99999999999d"), "error: value too large");
  EXPECT_EQ(duration("106752d"), "error: value too large");  // beyond int64 nanoseconds
  EXPECT_EQ(duration("106751d"), "9223286400000000000");
  uint64_t ns = 0;
  bool negative = false;
  LiteralError why;
  EXPECT_FALSE(decodeDuration("-", ns, negative, why));
  EXPECT_EQ(why.kind, LiteralError::Kind::Empty);
  EXPECT_FALSE(decodeDuration("99999999999d", ns, negative, why));
  EXPECT_EQ(why.kind, LiteralError::Kind::TooLarge);
  EXPECT_FALSE(decodeDuration("5x", ns, negative, why));
  EXPECT_EQ(why.kind, LiteralError::Kind::Malformed);
}

TEST(LiteralSyntax, TimeBodiesInTheirTypesUnits) {
  EXPECT_EQ(body("1s500ms", LiteralFamily::Time), "1500");
  EXPECT_EQ(body("-1.5ms", LiteralFamily::Time), "-1");  // TIME counts ms, truncated toward zero
  EXPECT_EQ(body("1.5us", LiteralFamily::Time), "0");
  EXPECT_EQ(body("1.5us", LiteralFamily::Ltime), "1500");
  EXPECT_EQ(body("1s5ns", LiteralFamily::Ltime), "1000000005");
  EXPECT_EQ(body("-2m", LiteralFamily::Ltime), "-120000000000");
  EXPECT_EQ(body("1s", LiteralFamily::None), "error: not a time or date literal");
}

TEST(LiteralSyntax, Dates) {
  EXPECT_EQ(body("1970-01-01", LiteralFamily::Date), "0");
  EXPECT_EQ(body("2024-01-02", LiteralFamily::Date), "1704153600");
  EXPECT_EQ(body("2024-1-2", LiteralFamily::Date), "1704153600");
  EXPECT_EQ(body("2024-02-29", LiteralFamily::Date), "1709164800");
  EXPECT_EQ(body("9999-12-31", LiteralFamily::Date), "253402214400");
  EXPECT_EQ(body("2023-02-29", LiteralFamily::Date), "error: no such date");
  EXPECT_EQ(body("2024-02-31", LiteralFamily::Date), "error: no such date");
  EXPECT_EQ(body("1969-12-31", LiteralFamily::Date),
            "error: before 1970: DATE and DT count unsigned seconds since 1970 (LDATE and LDT reach back to 1677)");
  // LDATE/LDT are signed 64-bit ns: before 1970 they are negative, down to 1677-09-21-00:12:43.145224192.
  EXPECT_EQ(body("1969-12-31", LiteralFamily::Ldate), "-86400000000000");
  EXPECT_EQ(body("1969-07-20-20:17:40", LiteralFamily::Ldt), "-14182940000000000");
  EXPECT_EQ(body("1677-09-21-00:12:43.145224192", LiteralFamily::Ldt), "-9223372036854775808");
  EXPECT_EQ(body("1677-09-21-00:12:43.145224191", LiteralFamily::Ldt),
            "error: before LDT#1677-09-21-00:12:43.145224192, the first of 64-bit nanoseconds");
  EXPECT_EQ(body("1677-09-21", LiteralFamily::Ldate), "error: before LDT#1677-09-21-00:12:43.145224192, the first of 64-bit nanoseconds");
  EXPECT_EQ(body("1676-12-31", LiteralFamily::Ldate), "error: before 1677: LDATE and LDT count signed 64-bit nanoseconds since 1970");
  EXPECT_EQ(body("2024-13-01", LiteralFamily::Date), "error: no such date");
  EXPECT_EQ(body("2024-01", LiteralFamily::Date), "error: expected yyyy-mm-dd");
  EXPECT_EQ(body("2024-01-02-03", LiteralFamily::Date), "error: expected yyyy-mm-dd");
  EXPECT_EQ(body(" 2024-01-02", LiteralFamily::Date), "error: expected yyyy-mm-dd");
}

TEST(LiteralSyntax, TimesOfDay) {
  EXPECT_EQ(body("00:00", LiteralFamily::Tod), "0");
  EXPECT_EQ(body("12:30", LiteralFamily::Tod), "45000000");
  EXPECT_EQ(body("12:30:00.5", LiteralFamily::Tod), "45000500");
  EXPECT_EQ(body("1:2:3", LiteralFamily::Tod), "3723000");
  EXPECT_EQ(body("23:59:59.999", LiteralFamily::Tod), "86399999");
  EXPECT_EQ(body("12:30:00.1239", LiteralFamily::Tod), "45000123");  // digits below 1 ms are dropped
  EXPECT_EQ(body("12:30:00.", LiteralFamily::Tod), "45000000");
  EXPECT_EQ(body("24:00:00", LiteralFamily::Tod), "error: no such time of day");
  EXPECT_EQ(body("12:60", LiteralFamily::Tod), "error: no such time of day");
  EXPECT_EQ(body("12:30:60", LiteralFamily::Tod), "error: no such time of day");
  EXPECT_EQ(body("12", LiteralFamily::Tod), "error: expected hh:mm:ss");
  EXPECT_EQ(body("12:30:.5", LiteralFamily::Tod), "error: expected hh:mm:ss");
  EXPECT_EQ(body("12:30:0.5x", LiteralFamily::Tod), "error: malformed fraction of a second");
}

TEST(LiteralSyntax, DatesAndTimes) {
  EXPECT_EQ(body("2024-01-02-12:30:00", LiteralFamily::Dt), "1704198600");
  EXPECT_EQ(body("2024-01-02-12:30:00.9", LiteralFamily::Dt), "1704198600");  // DT counts seconds
  EXPECT_EQ(body("2024-01-02-12:30", LiteralFamily::Dt), "1704198600");
  EXPECT_EQ(body("2024-01-02", LiteralFamily::Dt), "error: expected yyyy-mm-dd-hh:mm:ss");
  EXPECT_EQ(body("2024-02-30-00:00", LiteralFamily::Dt), "error: no such date");
  EXPECT_EQ(body("2024-01-02-25:00", LiteralFamily::Dt), "error: no such time of day");
}

TEST(LiteralSyntax, DigitsOfEveryBase) {
  uint64_t v = 0;
  EXPECT_TRUE(parseDigits("1010_1010", 2, v));
  EXPECT_EQ(v, 170u);
  EXPECT_TRUE(parseDigits("17", 8, v));
  EXPECT_EQ(v, 15u);
  EXPECT_TRUE(parseDigits("fF_ff", 16, v));
  EXPECT_EQ(v, 0xFFFFu);
  EXPECT_TRUE(parseDigits("FFFFFFFFFFFFFFFF", 16, v));
  EXPECT_EQ(v, UINT64_MAX);
  EXPECT_TRUE(parseDecimal("18446744073709551615", v));
  EXPECT_EQ(v, UINT64_MAX);
  EXPECT_TRUE(parseDecimal("_1__0_", v));  // underscores anywhere: callers that care check the ends
  EXPECT_EQ(v, 10u);
  EXPECT_FALSE(parseDecimal("18446744073709551616", v));
  EXPECT_FALSE(parseDigits("10000000000000000", 16, v));
  EXPECT_FALSE(parseDigits("102", 2, v));
  EXPECT_FALSE(parseDigits("8", 8, v));
  EXPECT_FALSE(parseDigits("G", 16, v));
  EXPECT_FALSE(parseDecimal("", v));
  EXPECT_FALSE(parseDecimal("__", v));
  EXPECT_FALSE(parseDecimal("1 2", v));
  EXPECT_FALSE(parseDecimal("-1", v));
}

TEST(LiteralSyntax, OnlyTheIecRadixes) {
  for (const char* radix : {"2", "8", "16", "016", "1_6"}) {
    unsigned base = 0;
    EXPECT_TRUE(parseRadix(radix, base)) << radix;
  }
  for (const char* radix : {"10", "3", "36", "", "x", "-2"}) {
    unsigned base = 7;
    EXPECT_FALSE(parseRadix(radix, base)) << radix;
    EXPECT_EQ(base, 7u) << radix;
  }
}

// The printer writes every unit of the table and the reader takes back what it wrote.
TEST(LiteralSyntax, PrinterAndReaderShareTheUnitTable) {
  for (const DurationUnit& unit : kDurationUnits) {
    std::string printed = formatLtimeNs(static_cast<int64_t>(unit.ns) * 3);
    EXPECT_EQ(printed, "LTIME#3" + std::string(unit.iec));
    EXPECT_EQ(duration(printed.substr(printed.find('#') + 1)), std::to_string(unit.ns * 3)) << printed;
    EXPECT_EQ(iecDurationUnit(asciiUpper(unit.iec)), &unit);
  }
  EXPECT_EQ(formatTimeMs(90061001), "T#1d1h1m1s1ms");
  EXPECT_EQ(formatLtimeNs(-90061001001001), "LTIME#-1d1h1m1s1ms1us1ns");
}

TEST(LiteralSyntax, UnitLookups) {
  EXPECT_EQ(iecDurationUnit("MS")->ns, 1'000'000u);
  EXPECT_EQ(iecDurationUnit("min"), nullptr);
  EXPECT_EQ(iecDurationUnitAtStart("ms5")->iec, "ms");
  EXPECT_EQ(iecDurationUnitAtStart("m5")->iec, "m");
  EXPECT_EQ(iecDurationUnitAtStart("NS")->iec, "ns");
  EXPECT_EQ(iecDurationUnitAtStart("x"), nullptr);
  EXPECT_EQ(quantityDurationUnit("min")->ns, 60'000'000'000u);
  EXPECT_EQ(quantityDurationUnit("m"), nullptr);  // metres in a cell file
  EXPECT_EQ(quantityDurationUnit("d"), nullptr);
  EXPECT_EQ(quantityDurationUnit("MS"), nullptr);  // cell-file units are case-sensitive
  EXPECT_EQ(quantityDurationUnit("ms")->ns, 1'000'000u);
}

}  // namespace
}  // namespace virtcom
