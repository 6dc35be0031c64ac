// The cell file's `plan:` section (docs/cell-file.md, "plan"): shifts read into Cell::plan, and
// every mistake at its position (C010, C011, C050).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cell_files.hpp"

namespace virtcom::cell::test {
namespace {

using ::testing::ElementsAre;

// No PLC: the section needs nothing else. Line 6 is the first line after it.
constexpr const char* kDevices = R"(devices:
  - name: Clamp
    type: timed
    commands:
      1: { name: Close, duration: 1 s }
)";

using PlanSection = CellFiles;

TEST_F(PlanSection, ShiftsAreReadInMinutesOfTheDay) {
  auto cell = loads(std::string(kDevices) +
                    "plan:\n"
                    "  shifts:\n"
                    "    - { name: Early, start: \"06:00\", end: \"14:00\", parts: 400 }\n"
                    "    - { name: Late, start: \"14:00\", end: \"22:30\", parts: 380 }\n"
                    "    - { name: Night, start: \"22:30\", end: \"06:00\", parts: 0 }\n");
  ASSERT_TRUE(cell);
  const auto& shifts = cell->plan.shifts;
  ASSERT_EQ(shifts.size(), 3u);
  EXPECT_EQ(shifts[0].name, "Early");
  EXPECT_EQ(shifts[0].startMin, 360);
  EXPECT_EQ(shifts[0].endMin, 840);
  EXPECT_EQ(shifts[0].parts, 400u);
  EXPECT_EQ(shifts[1].endMin, 22 * 60 + 30);
  EXPECT_EQ(shifts[2].startMin, 22 * 60 + 30);
  EXPECT_EQ(shifts[2].endMin, 360);  // past midnight
  EXPECT_EQ(shifts[2].parts, 0u);
}

TEST_F(PlanSection, MidnightEndsAsTwentyFourHundred) {
  auto cell = loads(std::string(kDevices) + "plan:\n  shifts:\n    - { name: Day, start: \"00:00\", end: \"24:00\", parts: 10 }\n");
  ASSERT_TRUE(cell);
  EXPECT_EQ(cell->plan.shifts[0].startMin, 0);
  EXPECT_EQ(cell->plan.shifts[0].endMin, 0);  // a whole day
}

TEST_F(PlanSection, NoPlanIsAnEmptyOne) {
  auto cell = loads(kDevices);
  ASSERT_TRUE(cell);
  EXPECT_TRUE(cell->plan.shifts.empty());
}

TEST_F(PlanSection, BadTimesPartsNamesAndOverlapsAreC050) {
  EXPECT_THAT(fails(std::string(kDevices) +
                    "plan:\n"
                    "  shifts:\n"
                    "    - { name: Early, start: \"6:00\", end: \"14:00\", parts: 400 }\n"
                    "    - { name: Late, start: \"14:00\", end: \"24:30\", parts: -1 }\n"
                    "    - { name: A, start: \"06:00\", end: \"14:00\", parts: 1 }\n"
                    "    - { name: A, start: \"14:00\", end: \"15:00\", parts: 1 }\n"
                    "    - { name: B, start: \"13:00\", end: \"07:00\", parts: 1 }\n"),
              ElementsAre("cell.yaml:8:29: error[C050]: 'start' is '6:00', expected a time of day as HH:MM (e.g. \"06:00\")",
                          "cell.yaml:9:42: error[C050]: 'end' is '24:30', expected a time of day as HH:MM (e.g. \"06:00\"; \"24:00\" for midnight)",
                          "cell.yaml:9:58: error[C050]: 'parts' is -1, expected a count of parts (0 or more)",
                          "cell.yaml:11:15: error[C050]: a shift named 'A' is already planned (names are unique)",
                          "cell.yaml:12:7: error[C050]: shift 'B' overlaps shift 'A': a moment of the day belongs to one shift"));
}

TEST_F(PlanSection, ShiftsAreRequiredAndKeysChecked) {
  EXPECT_THAT(fails(std::string(kDevices) + "plan:\n  shift: []\n"),
              ElementsAre("cell.yaml:7:3: error[C050]: 'plan' needs 'shifts:', a list of shifts, e.g. - { name: Early, start: \"06:00\", "
                          "end: \"14:00\", parts: 400 }",
                          "cell.yaml:7:3: error[C011]: unknown key 'shift' in 'plan' (expected one of: shifts)"));
  EXPECT_THAT(fails(std::string(kDevices) + "plan:\n  shifts:\n    - { name: Early, start: \"06:00\", parts: many, colour: red }\n"),
              ElementsAre("cell.yaml:8:7: error[C010]: a shift of 'plan: shifts' needs 'end'",
                          "cell.yaml:8:45: error[C010]: 'parts' must be a whole number, found 'many'",
                          "cell.yaml:8:51: error[C011]: unknown key 'colour' in a shift of 'plan: shifts' (expected one of: name, start, end, parts)"));
}

}  // namespace
}  // namespace virtcom::cell::test
