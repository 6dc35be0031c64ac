// IEC literal forms of values (what `virtcom exec --print` shows) and the calendar helpers.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "core/iec_value.hpp"

namespace virtcom {
namespace {

TEST(FormatTime, ZeroIsZeroMilliseconds) { EXPECT_EQ(formatTimeMs(0), "T#0ms"); }

TEST(FormatTime, OmitsZeroUnits) {
  EXPECT_EQ(formatTimeMs(1), "T#1ms");
  EXPECT_EQ(formatTimeMs(1500), "T#1s500ms");
  EXPECT_EQ(formatTimeMs(2000), "T#2s");
  EXPECT_EQ(formatTimeMs(90'000), "T#1m30s");
  EXPECT_EQ(formatTimeMs(3'600'000), "T#1h");
  EXPECT_EQ(formatTimeMs(3'600'001), "T#1h1ms");
}

TEST(FormatTime, Days) {
  EXPECT_EQ(formatTimeMs(86'400'000), "T#1d");
  EXPECT_EQ(formatTimeMs(86'400'000 + 3'600'000 + 60'000 + 1000 + 1), "T#1d1h1m1s1ms");
  EXPECT_EQ(formatTimeMs(int64_t{3} * 86'400'000 + 7), "T#3d7ms");
}

TEST(FormatTime, Negative) {
  EXPECT_EQ(formatTimeMs(-1), "T#-1ms");
  EXPECT_EQ(formatTimeMs(-2000), "T#-2s");
  EXPECT_EQ(formatTimeMs(-90'500), "T#-1m30s500ms");
}

TEST(FormatTime, FullRangeOfThe32BitTime) {
  EXPECT_EQ(formatTimeMs(INT32_MAX), "T#24d20h31m23s647ms");
  EXPECT_EQ(formatTimeMs(INT32_MIN), "T#-24d20h31m23s648ms");
}

TEST(FormatLtime, UnitsDownToNanoseconds) {
  EXPECT_EQ(formatLtimeNs(0), "LTIME#0ns");
  EXPECT_EQ(formatLtimeNs(1), "LTIME#1ns");
  EXPECT_EQ(formatLtimeNs(1'000'000'005), "LTIME#1s5ns");
  EXPECT_EQ(formatLtimeNs(1'500'000), "LTIME#1ms500us");
  EXPECT_EQ(formatLtimeNs(int64_t{86'400} * 1'000'000'000 + 1000), "LTIME#1d1us");
  EXPECT_EQ(formatLtimeNs(-1'000'001), "LTIME#-1ms1ns");
}

TEST(FormatLtime, Int64Max) {
  EXPECT_EQ(formatLtimeNs(INT64_MAX), "LTIME#106751d23h47m16s854ms775us807ns");
}

// Regression test (was a bug found by the e2e/unit suites).
TEST(FormatLtime, Int64MinIsFormattedWithoutOverflow) {
  EXPECT_EQ(formatLtimeNs(INT64_MIN), "LTIME#-106751d23h47m16s854ms775us808ns");
}

TEST(FormatDate, Epoch) { EXPECT_EQ(formatDate(0), "D#1970-01-01"); }

TEST(FormatDate, KnownDates) {
  EXPECT_EQ(formatDate(int64_t{19'723} * 86'400), "D#2024-01-01");
  EXPECT_EQ(formatDate(int64_t{19'782} * 86'400), "D#2024-02-29");
  EXPECT_EQ(formatDate(int64_t{24'855} * 86'400), "D#2038-01-19");
}

TEST(FormatDate, TimeWithinTheDayIsIgnored) {
  EXPECT_EQ(formatDate(86'399), "D#1970-01-01");
  EXPECT_EQ(formatDate(86'400), "D#1970-01-02");
}

TEST(FormatDate, BeforeTheEpochUsesTheDayContainingTheSecond) {
  EXPECT_EQ(formatDate(-1), "D#1969-12-31");
  EXPECT_EQ(formatDate(-86'400), "D#1969-12-31");
  EXPECT_EQ(formatDate(-86'401), "D#1969-12-30");
}

TEST(FormatTimeOfDay, WholeSeconds) {
  EXPECT_EQ(formatTimeOfDay(0), "TOD#00:00:00");
  EXPECT_EQ(formatTimeOfDay(45'000'000), "TOD#12:30:00");
  EXPECT_EQ(formatTimeOfDay(86'399'000), "TOD#23:59:59");
}

TEST(FormatTimeOfDay, FractionWithoutTrailingZeros) {
  EXPECT_EQ(formatTimeOfDay(45'000'500), "TOD#12:30:00.5");
  EXPECT_EQ(formatTimeOfDay(45'000'050), "TOD#12:30:00.05");
  EXPECT_EQ(formatTimeOfDay(45'000'001), "TOD#12:30:00.001");
  EXPECT_EQ(formatTimeOfDay(45'015'120), "TOD#12:30:15.12");
  EXPECT_EQ(formatTimeOfDay(86'399'999), "TOD#23:59:59.999");
}

TEST(FormatDateAndTime, Epoch) { EXPECT_EQ(formatDateAndTime(0), "DT#1970-01-01-00:00:00"); }

TEST(FormatDateAndTime, KnownInstant) {
  EXPECT_EQ(formatDateAndTime(1'704'198'600), "DT#2024-01-02-12:30:00");
}

TEST(FormatDateAndTime, BeforeTheEpoch) {
  EXPECT_EQ(formatDateAndTime(-1), "DT#1969-12-31-23:59:59");
  EXPECT_EQ(formatDateAndTime(-14'182'940), "DT#1969-07-20-20:17:40");
  EXPECT_EQ(formatDateAndTime(-86'400), "DT#1969-12-31-00:00:00");
}

TEST(FormatReal, AlwaysHasAPointOrAnExponent) {
  EXPECT_EQ(formatReal(1.5f), "1.5");
  EXPECT_EQ(formatReal(2.0f), "2.0");
  EXPECT_EQ(formatReal(0.0f), "0.0");
  EXPECT_EQ(formatReal(-3.0f), "-3.0");
  EXPECT_EQ(formatReal(100.0f), "100.0");
}

TEST(FormatReal, ShortestRoundTripOfTheFloat) {
  EXPECT_EQ(formatReal(0.1f), "0.1");
  EXPECT_EQ(formatReal(1.0f / 3.0f), "0.33333334");
  EXPECT_EQ(formatReal(16'777'216.0f), "16777216.0");
}

TEST(FormatReal, ExponentIsUpperCase) {
  EXPECT_EQ(formatReal(1e20f), "1E+20");
  EXPECT_EQ(formatReal(-1e20f), "-1E+20");
  EXPECT_EQ(formatReal(1e-7f), "1E-07");
  EXPECT_EQ(formatReal(3.4028235e38f), "3.4028235E+38");
}

TEST(FormatReal, NegativeZeroKeepsItsSign) { EXPECT_EQ(formatReal(-0.0f), "-0.0"); }

TEST(FormatReal, NanAndInfinityGetNoDecimalSuffix) {
  EXPECT_EQ(formatReal(std::numeric_limits<float>::quiet_NaN()), "nan");
  EXPECT_EQ(formatReal(std::numeric_limits<float>::infinity()), "inf");
  EXPECT_EQ(formatReal(-std::numeric_limits<float>::infinity()), "-inf");
}

TEST(FormatLreal, ShortestRoundTripOfTheDouble) {
  EXPECT_EQ(formatLreal(3.0), "3.0");
  EXPECT_EQ(formatLreal(0.1), "0.1");
  EXPECT_EQ(formatLreal(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(formatLreal(1e100), "1E+100");
  EXPECT_EQ(formatLreal(-2.5e-300), "-2.5E-300");
}

TEST(FormatLreal, NanAndInfinity) {
  EXPECT_EQ(formatLreal(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(formatLreal(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(formatLreal(-std::numeric_limits<double>::infinity()), "-inf");
}

TEST(QuoteString, PlainAndEmpty) {
  EXPECT_EQ(quoteString(""), "''");
  EXPECT_EQ(quoteString("abc"), "'abc'");
  EXPECT_EQ(quoteString("say \"hi\""), "'say \"hi\"'");  // $" is only needed in WSTRING
}

TEST(QuoteString, EveryDollarEscape) {
  EXPECT_EQ(quoteString("it's"), "'it$'s'");
  EXPECT_EQ(quoteString("$"), "'$$'");
  EXPECT_EQ(quoteString("a\nb"), "'a$Nb'");
  EXPECT_EQ(quoteString("\r"), "'$R'");
  EXPECT_EQ(quoteString("\t"), "'$T'");
  EXPECT_EQ(quoteString("\f"), "'$P'");
}

TEST(QuoteString, OtherControlAndNonAsciiBytesAsTwoHexDigits) {
  EXPECT_EQ(quoteString(std::string_view("\x00", 1)), "'$00'");
  EXPECT_EQ(quoteString("\x01"), "'$01'");
  EXPECT_EQ(quoteString("\x1b"), "'$1B'");
  EXPECT_EQ(quoteString("\x7f"), "'$7F'");
  EXPECT_EQ(quoteString("\xe4"), "'$E4'");
  EXPECT_EQ(quoteString("\xff"), "'$FF'");
}

TEST(QuoteString, EscapesCombine) { EXPECT_EQ(quoteString("$'$\n"), "'$$$'$$$N'"); }

TEST(Calendar, KnownDays) {
  EXPECT_EQ(daysFromCivil(1970, 1, 1), 0);
  EXPECT_EQ(daysFromCivil(1969, 12, 31), -1);
  EXPECT_EQ(daysFromCivil(2000, 3, 1), 11'017);
  EXPECT_EQ(daysFromCivil(2024, 2, 29), 19'782);
  EXPECT_EQ(daysFromCivil(1900, 3, 1), -25'508);
  EXPECT_EQ(daysFromCivil(1600, 2, 29), -135'081);
  EXPECT_EQ(daysFromCivil(1, 1, 1), -719'162);
  EXPECT_EQ(daysFromCivil(9999, 12, 31), 2'932'896);
}

TEST(Calendar, LeapYearRules) {
  // divisible by 4: leap; by 100: not; by 400: leap
  EXPECT_EQ(daysFromCivil(2024, 3, 1) - daysFromCivil(2024, 2, 28), 2);
  EXPECT_EQ(daysFromCivil(2023, 3, 1) - daysFromCivil(2023, 2, 28), 1);
  EXPECT_EQ(daysFromCivil(1900, 3, 1) - daysFromCivil(1900, 2, 28), 1);
  EXPECT_EQ(daysFromCivil(2100, 3, 1) - daysFromCivil(2100, 2, 28), 1);
  EXPECT_EQ(daysFromCivil(2000, 3, 1) - daysFromCivil(2000, 2, 28), 2);
  EXPECT_EQ(daysFromCivil(2001, 1, 1) - daysFromCivil(2000, 1, 1), 366);
  EXPECT_EQ(daysFromCivil(1901, 1, 1) - daysFromCivil(1900, 1, 1), 365);
}

TEST(Calendar, CivilFromDaysKnownDates) {
  int64_t y = 0;
  unsigned m = 0, d = 0;
  civilFromDays(0, y, m, d);
  EXPECT_EQ(std::tuple(y, m, d), std::tuple(int64_t{1970}, 1u, 1u));
  civilFromDays(-1, y, m, d);
  EXPECT_EQ(std::tuple(y, m, d), std::tuple(int64_t{1969}, 12u, 31u));
  civilFromDays(19'782, y, m, d);
  EXPECT_EQ(std::tuple(y, m, d), std::tuple(int64_t{2024}, 2u, 29u));
  civilFromDays(-135'081, y, m, d);
  EXPECT_EQ(std::tuple(y, m, d), std::tuple(int64_t{1600}, 2u, 29u));
}

// Every day from year 1 to 9999 round-trips, and consecutive days are consecutive dates.
// (Plain comparisons in the loop: 3.6 million gtest assertions would dominate the run time.)
TEST(Calendar, RoundTripOverTheWholeFourDigitRange) {
  int64_t py = 0;
  unsigned pm = 12, pd = 31;
  for (int64_t z = daysFromCivil(1, 1, 1); z <= daysFromCivil(9999, 12, 31); ++z) {
    int64_t y;
    unsigned m, d;
    civilFromDays(z, y, m, d);
    bool nextDay = (y == py && m == pm && d == pd + 1) || (y == py && m == pm + 1 && d == 1) ||
                   (y == py + 1 && m == 1 && d == 1 && pm == 12 && pd == 31);
    if (daysFromCivil(y, m, d) != z || !nextDay) {
      FAIL() << "day " << z << " is " << y << "-" << m << "-" << d << " (after " << py << "-" << pm << "-" << pd
             << "), which maps back to day " << daysFromCivil(y, m, d);
    }
    py = y, pm = m, pd = d;
  }
  EXPECT_EQ(py, 9999);
}

TEST(ElemTypeByName, StandardNamesCaseInsensitive) {
  ElemType t{};
  ASSERT_TRUE(elemTypeByName("INT", t));
  EXPECT_EQ(t, ElemType::Int);
  ASSERT_TRUE(elemTypeByName("lreal", t));
  EXPECT_EQ(t, ElemType::Lreal);
  ASSERT_TRUE(elemTypeByName("Time_Of_Day", t));
  EXPECT_EQ(t, ElemType::Tod);
  ASSERT_TRUE(elemTypeByName("date_and_time", t));
  EXPECT_EQ(t, ElemType::Dt);
  ASSERT_TRUE(elemTypeByName("wString", t));
  EXPECT_EQ(t, ElemType::Wstring);
}

TEST(ElemTypeByName, ShortAliasesTodAndDt) {
  ElemType t{};
  ASSERT_TRUE(elemTypeByName("TOD", t));
  EXPECT_EQ(t, ElemType::Tod);
  ASSERT_TRUE(elemTypeByName("tod", t));
  EXPECT_EQ(t, ElemType::Tod);
  ASSERT_TRUE(elemTypeByName("DT", t));
  EXPECT_EQ(t, ElemType::Dt);
  ASSERT_TRUE(elemTypeByName("dT", t));
  EXPECT_EQ(t, ElemType::Dt);
}

TEST(ElemTypeByName, UnknownNames) {
  ElemType t{};
  EXPECT_FALSE(elemTypeByName("", t));
  EXPECT_FALSE(elemTypeByName("INTEGER", t));
  EXPECT_FALSE(elemTypeByName("IN", t));
  EXPECT_FALSE(elemTypeByName("TOD ", t));
  EXPECT_FALSE(elemTypeByName("D", t));
}

TEST(ElemTypeByName, EveryTableEntryFindsItself) {
  for (int i = 0; i <= static_cast<int>(ElemType::Wstring); ++i) {
    ElemType t{};
    auto want = static_cast<ElemType>(i);
    ASSERT_TRUE(elemTypeByName(elemTypeInfo(want).name, t)) << elemTypeInfo(want).name;
    EXPECT_EQ(t, want) << elemTypeInfo(want).name;
  }
}

TEST(ElemTypeInfo, SizesAndBitWidths) {
  EXPECT_EQ(elemTypeInfo(ElemType::Lint).sizeBytes, 8u);
  EXPECT_EQ(elemTypeInfo(ElemType::Time).sizeBytes, 4u);
  EXPECT_EQ(elemTypeInfo(ElemType::Ltime).sizeBytes, 8u);
  EXPECT_EQ(elemTypeInfo(ElemType::String).sizeBytes, 0u);
  EXPECT_EQ(bitWidth(ElemType::Bool), 1u);
  EXPECT_EQ(bitWidth(ElemType::Byte), 8u);
  EXPECT_EQ(bitWidth(ElemType::Udint), 32u);
  EXPECT_TRUE(isInteger(ElemType::Word));
  EXPECT_TRUE(isSignedInt(ElemType::Sint));
  EXPECT_FALSE(isSignedInt(ElemType::Usint));
  EXPECT_TRUE(isFloat(ElemType::Real));
  EXPECT_FALSE(isInteger(ElemType::Time));
}

// The VM formats whatever bits a faulty program holds (regression: a TOD of -1 ms overran the
// formatting buffer).
TEST(FormatDates, AnyBitsStayWithinTheBuffer) {
  EXPECT_EQ(formatTimeOfDay(-1), "TOD#23:59:59.999");
  EXPECT_EQ(formatTimeOfDay(86400000 + 1500), "TOD#00:00:01.5");
  for (int64_t v : {std::numeric_limits<int64_t>::min(), std::numeric_limits<int64_t>::max(), int64_t{-1}}) {
    char buf[kIecTextMax];
    EXPECT_LE(formatDateAndTimeInto(buf, v), kIecTextMax);
    EXPECT_LE(formatDateInto(buf, v), kIecTextMax);
    EXPECT_LE(formatTimeOfDayInto(buf, v), kIecTextMax);
    EXPECT_LE(formatLtimeNsInto(buf, v), kIecTextMax);
    EXPECT_LE(formatTimeMsInto(buf, v), kIecTextMax);
  }
  EXPECT_EQ(formatDate(-1), "D#1969-12-31");
}

}  // namespace
}  // namespace virtcom
