// Cell-file quantities: duration units come from core/duration_units, the others from the
// config tree's own table; spellings are exact and `m` stays metres.
#include <gtest/gtest.h>

#include <string>

#include "core/config_node.hpp"

namespace virtcom {
namespace {

double si(const std::string& text, Dimension dim) {
  double value = -1;
  std::string problem = parseQuantity(text, dim, value);
  EXPECT_EQ(problem, "") << text;
  return value;
}

std::string problem(const std::string& text, Dimension dim) {
  double value = 0;
  return parseQuantity(text, dim, value);
}

TEST(QuantityUnits, DurationsInSeconds) {
  EXPECT_EQ(si("150 ms", Dimension::Time), 150 * 1e-3);  // bit for bit what the decimal factor gives
  EXPECT_EQ(si("2 s", Dimension::Time), 2.0);
  EXPECT_EQ(si("5 min", Dimension::Time), 300.0);
  EXPECT_EQ(si("1.5h", Dimension::Time), 5400.0);
  EXPECT_EQ(si("250 us", Dimension::Time), 250 * 1e-6);
  EXPECT_EQ(si("7 ns", Dimension::Time), 7 * 1e-9);
}

TEST(QuantityUnits, SpellingsAreExactAndMIsMetres) {
  EXPECT_EQ(si("1 m", Dimension::Length), 1.0);
  EXPECT_EQ(si("250 mm", Dimension::Length), 250 * 1e-3);
  EXPECT_EQ(problem("1 m", Dimension::Time), "'1 m' is not a duration (e.g. 2 s, 150 ms)");
  EXPECT_EQ(problem("2 s", Dimension::Length), "'2 s' is not a length (e.g. 250 mm)");
  EXPECT_EQ(problem("1 MS", Dimension::Time), "unknown unit 'MS' in '1 MS': expected a duration (e.g. 2 s, 150 ms)");
  EXPECT_EQ(problem("1 d", Dimension::Time), "unknown unit 'd' in '1 d': expected a duration (e.g. 2 s, 150 ms)");
  EXPECT_EQ(problem("3", Dimension::Time), "'3' needs a unit: expected a duration (e.g. 2 s, 150 ms)");
}

}  // namespace
}  // namespace virtcom
