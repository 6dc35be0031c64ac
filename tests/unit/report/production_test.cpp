// Planned vs actual production per shift and day, and the stations' elapsed times
// (report/production.hpp), driven by an injected wall clock: local times built from a date and
// HH:MM, cycles completed handed in as the monitor's polls would.
#include "report/production.hpp"

#include <gtest/gtest.h>

namespace virtcom::report {
namespace {

constexpr int64_t kMinNs = 60'000'000'000;
// 2026-12-02 00:00 local: 20789 days after 1970-01-01.
constexpr int64_t kDec2 = 20789 * kDayNs;
int64_t at(int64_t day, int h, int m) { return day + (h * 60 + m) * kMinNs; }

ProductionPlan threeShifts() {
  ProductionPlan plan;
  plan.shifts.push_back({"Early", 6 * 60, 14 * 60, 400, {}});
  plan.shifts.push_back({"Late", 14 * 60, 22 * 60, 320, {}});
  plan.shifts.push_back({"Night", 22 * 60, 6 * 60, 80, {}});
  return plan;
}

TEST(Production, LocalDateOfAWallTime) {
  EXPECT_EQ(localDate(kDec2), "2026-12-02");
  EXPECT_EQ(localDate(at(kDec2, 23, 59)), "2026-12-02");
  EXPECT_EQ(localDate(kDec2 + kDayNs), "2026-12-03");
  EXPECT_EQ(localDate(0), "1970-01-01");
}

TEST(Production, CyclesCountIntoTheShiftTheClockIsIn) {
  ProductionPlan plan = threeShifts();
  ProductionCounter counter(plan);
  counter.update(at(kDec2, 13, 0), 0);   // joined an hour before the end of Early
  counter.update(at(kDec2, 13, 30), 5);
  counter.update(at(kDec2, 14, 0), 7);   // Late begins: 2 more, counted at the first poll of Late
  counter.update(at(kDec2, 15, 0), 17);
  ASSERT_EQ(counter.shifts().size(), 2u);
  EXPECT_EQ(counter.shifts()[0].shift, 0u);
  EXPECT_EQ(counter.shifts()[0].actual, 5u);
  EXPECT_EQ(counter.shifts()[0].watchedFromNs, at(kDec2, 13, 0));
  EXPECT_EQ(counter.shifts()[1].shift, 1u);
  EXPECT_EQ(counter.shifts()[1].actual, 12u);
  EXPECT_EQ(counter.shifts()[1].watchedFromNs, at(kDec2, 14, 0));  // watched from its start
}

TEST(Production, ThePlanIsProRatedToTheWatchedPartOfAShift) {
  ProductionPlan plan = threeShifts();
  ProductionCounter counter(plan);
  counter.update(at(kDec2, 13, 0), 0);
  counter.update(at(kDec2, 13, 59), 60);
  counter.update(at(kDec2, 16, 0), 130);
  Trace trace;
  ProductionReport r = productionReport(counter, at(kDec2, 16, 0), trace, 0);
  ASSERT_EQ(r.shifts.size(), 2u);
  EXPECT_EQ(r.shifts[0].day, "2026-12-02");
  EXPECT_EQ(r.shifts[0].name, "Early");
  EXPECT_EQ(r.shifts[0].plan, 400u);
  EXPECT_DOUBLE_EQ(r.shifts[0].planNow, 50);  // one hour of eight: 400 / 8
  EXPECT_EQ(r.shifts[0].actual, 60u);
  EXPECT_DOUBLE_EQ(r.shifts[1].planNow, 80);  // two hours of eight: 320 / 4
  EXPECT_EQ(r.shifts[1].actual, 70u);
  ASSERT_EQ(r.days.size(), 1u);
  EXPECT_EQ(r.days[0].plan, 720u);
  EXPECT_DOUBLE_EQ(r.days[0].planNow, 130);
  EXPECT_EQ(r.days[0].actual, 130u);
}

TEST(Production, TheCurrentShiftIsTheOneTheLastUpdateWasIn) {
  ProductionPlan plan;
  plan.shifts.push_back({"Early", 6 * 60, 14 * 60, 400, {}});
  ProductionCounter counter(plan);
  EXPECT_EQ(counter.current(), nullptr);
  counter.update(at(kDec2, 10, 0), 0);
  counter.update(at(kDec2, 12, 0), 30);
  ASSERT_NE(counter.current(), nullptr);
  EXPECT_EQ(counter.current()->actual, 30u);
  EXPECT_EQ(counter.lastNs(), at(kDec2, 12, 0));
  EXPECT_DOUBLE_EQ(planNow(plan.shifts[0], *counter.current(), counter.lastNs()), 100);  // 2 of 8 hours
  counter.update(at(kDec2, 14, 0), 31);
  EXPECT_EQ(counter.current(), nullptr);  // between shifts
}

TEST(Production, ANightShiftBelongsToTheDayItStarted) {
  ProductionPlan plan = threeShifts();
  ProductionCounter counter(plan);
  counter.update(at(kDec2, 23, 0), 0);
  counter.update(at(kDec2 + kDayNs, 2, 0), 9);  // after midnight, still Night
  counter.update(at(kDec2 + kDayNs, 6, 0), 10); // Early of Dec 3
  ProductionReport r = productionReport(counter, at(kDec2 + kDayNs, 6, 0), Trace{}, 0);
  ASSERT_EQ(r.shifts.size(), 2u);
  EXPECT_EQ(r.shifts[0].name, "Night");
  EXPECT_EQ(r.shifts[0].day, "2026-12-02");
  EXPECT_EQ(r.shifts[0].actual, 9u);
  EXPECT_DOUBLE_EQ(r.shifts[0].planNow, 70);  // 7 of 8 hours watched: 80 × 7/8
  EXPECT_EQ(r.shifts[1].day, "2026-12-03");
  ASSERT_EQ(r.days.size(), 2u);
}

TEST(Production, JoinedAtNightAfterMidnightFindsYesterdaysShift) {
  ProductionPlan plan = threeShifts();
  ProductionCounter counter(plan);
  counter.update(at(kDec2, 3, 0), 0);
  ASSERT_EQ(counter.shifts().size(), 1u);
  EXPECT_EQ(counter.shifts()[0].startNs, at(kDec2 - kDayNs, 22, 0));
}

TEST(Production, CyclesBetweenShiftsCountNowhere) {
  ProductionPlan plan;
  plan.shifts.push_back({"Early", 6 * 60, 14 * 60, 400, {}});
  ProductionCounter counter(plan);
  counter.update(at(kDec2, 15, 0), 3);
  counter.update(at(kDec2 + kDayNs, 5, 59), 10);  // no shift: not counted
  counter.update(at(kDec2 + kDayNs, 6, 0), 10);
  counter.update(at(kDec2 + kDayNs, 7, 0), 14);
  ASSERT_EQ(counter.shifts().size(), 1u);
  EXPECT_EQ(counter.shifts()[0].actual, 4u);
  EXPECT_EQ(localDate(counter.shifts()[0].startNs), "2026-12-03");
}

TEST(Production, StationsShowTheirCurrentOperationAndItsElapsedTime) {
  Trace trace;
  uint32_t clamp = trace.addDevice("Clamp", "timed"), press = trace.addDevice("Press", "press");
  uint32_t lock = trace.internLabel("Lock"), pin = trace.internLabel("PressPin");
  trace.endActivity(trace.beginActivity(clamp, lock, 0), 300'000'000, 0);
  trace.beginActivity(press, pin, 400'000'000);
  ProductionReport r = productionReport(ProductionCounter(ProductionPlan{}), 0, trace, 1'000'000'000);
  ASSERT_EQ(r.stations.size(), 2u);
  EXPECT_EQ(r.stations[0].name, "Clamp");
  EXPECT_EQ(r.stations[0].operation, "");  // idle
  EXPECT_EQ(r.stations[1].operation, "PressPin");
  EXPECT_EQ(r.stations[1].elapsedNs, 600'000'000);
  const std::string table = productionTable(r);
  EXPECT_NE(table.find("PressPin"), std::string::npos) << table;
  EXPECT_NE(table.find("0.600"), std::string::npos) << table;
  EXPECT_EQ(table.find("Shift"), std::string::npos) << table;  // no plan: no shift table
}

}  // namespace
}  // namespace virtcom::report
