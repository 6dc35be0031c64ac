// Signals of a recorded run as plots over a time range (HistoryReader::series): the value before
// the range, the changes in it, their decimation to min/max/last per bucket; and the plans of
// the range queries the HMI sends (they search an index, never scan a table).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>

#include "history/query.hpp"
#include "history/query_sql.hpp"
#include "history/schema.hpp"
#include "history_fixture.hpp"

namespace virtcom::history {
namespace {

class SeriesTest : public test::HistoryTest {
 protected:
  void SetUp() override {
    HistoryTest::SetUp();
    auto recorder = Recorder::open(path("h.sqlite"), {});
    ASSERT_TRUE(recorder.has_value());
    recordSample(**recorder);
  }
  HistoryReader reader() {
    auto reader = HistoryReader::open(path("h.sqlite"));
    EXPECT_TRUE(reader.has_value());
    return std::move(*reader);
  }
};

TEST_F(SeriesTest, ASeriesHasTheValueBeforeTheRangeAndItsChanges) {
  auto series = reader().series(1, {1}, {3'000'000, 5'000'000}, 100);
  ASSERT_EQ(series.size(), 1u);
  EXPECT_EQ(series[0].signal, 1u);
  EXPECT_EQ(series[0].before, 7u);  // MAIN.count at 2 ms
  ASSERT_EQ(series[0].points.size(), 3u);
  EXPECT_EQ(series[0].points[0].timeNs, 3'000'000);
  EXPECT_EQ(series[0].points[2].raw, 10u);
  EXPECT_FALSE(series[0].decimated());
  // Axis.pos never changed: its initial value, no points.
  auto still = reader().series(1, {2}, {}, 100);
  EXPECT_EQ(still[0].before, 0u);
  EXPECT_TRUE(still[0].points.empty());
}

TEST_F(SeriesTest, UnknownAndRepeatedSignalsAreLeftOut) {
  auto series = reader().series(1, {1, 9, 1, 0}, {}, 100);
  ASSERT_EQ(series.size(), 2u);
  EXPECT_EQ(series[0].signal, 1u);
  EXPECT_EQ(series[1].signal, 0u);
  EXPECT_TRUE(reader().series(5, {0}, {}, 100).empty());  // no such run
}

TEST_F(SeriesTest, ManyChangesAreCutIntoBucketsOfMinMaxAndLast) {
  // MAIN.count counts 6..15 over 1..10 ms: 6 points give two buckets of 5 ms, each its first
  // (smallest) and last (largest) change.
  auto series = reader().series(1, {1}, {}, 6);
  ASSERT_TRUE(series[0].decimated());
  EXPECT_EQ(series[0].changes, 10u);
  std::vector<uint64_t> values;
  for (const SignalChange& c : series[0].points) values.push_back(c.raw);
  EXPECT_EQ(values, (std::vector<uint64_t>{6, 10, 11, 15}));
}

TEST_F(SeriesTest, ASpikeSurvivesDecimation) {
  Trace t;
  t.signals = {{"Press.force", ElemType::Lreal, 0}};
  auto recorder = Recorder::open(path("spike.sqlite"), {});
  ASSERT_TRUE(recorder.has_value());
  (*recorder)->begin(t);
  for (int64_t i = 1; i <= 1000; ++i) {
    const double v = i == 500 ? 99.0 : i == 700 ? -5.0 : 1.0 + static_cast<double>(i % 2) * 0.01;
    SignalChange c{i * 1'000'000, 0, std::bit_cast<uint64_t>(v)};
    t.changes.push_back(c);
    (*recorder)->change(c);
    (*recorder)->tick(t, c.timeNs);
  }
  t.endNs = 1'000'000'000;
  (*recorder)->end(t);
  recorder->reset();
  auto reader = HistoryReader::open(path("spike.sqlite"));
  ASSERT_TRUE(reader.has_value());
  auto series = reader->series(1, {0}, {}, 30);
  ASSERT_EQ(series.size(), 1u);
  EXPECT_LE(series[0].points.size(), 30u);
  auto has = [&](double v) {
    return std::ranges::any_of(series[0].points, [v](const SignalChange& c) { return std::bit_cast<double>(c.raw) == v; });
  };
  EXPECT_TRUE(has(99.0));
  EXPECT_TRUE(has(-5.0));
  EXPECT_EQ(series[0].points.back().timeNs, 1'000'000'000);  // the last change: the value held after it
}

// The range queries search the tables' keys (EXPLAIN QUERY PLAN says SEARCH ... USING), never
// SCAN a whole table.
TEST_F(SeriesTest, RangeQueriesSearchAnIndex) {
  auto db = openDatabase(path("h.sqlite"), OpenMode::Read);
  ASSERT_TRUE(db.has_value()) << db.error();
  for (const char* sql : {sql::kChangesInRange, sql::kValueBefore, sql::kActivitiesInRange}) {
    Statement plan(*db, (std::string("EXPLAIN QUERY PLAN ") + sql).c_str());
    std::string details;
    while (plan.step()) details += plan.columnText(3) + "\n";
    EXPECT_NE(details.find("SEARCH"), std::string::npos) << sql << "\n" << details;
    EXPECT_NE(details.find("USING"), std::string::npos) << sql << "\n" << details;
    EXPECT_EQ(details.find("SCAN"), std::string::npos) << sql << "\n" << details;
  }
}

}  // namespace
}  // namespace virtcom::history
