// Time-range queries of a recorded run: changes, activities, values before a time, and a part
// of a run as a trace shifted to start at 0.
#include <gtest/gtest.h>

#include "history/query.hpp"
#include "history/schema.hpp"
#include "report/html_report.hpp"
#include "report/json_report.hpp"
#include "report/kpis.hpp"
#include "report/waveform.hpp"
#include "history_fixture.hpp"

namespace virtcom::history {
namespace {

class Query : public test::HistoryTest {
 protected:
  void SetUp() override {
    HistoryTest::SetUp();
    auto recorder = Recorder::open(path("h.sqlite"), {});
    ASSERT_TRUE(recorder.has_value());
    recorded_ = recordSample(**recorder);
    recorder->reset();
    auto reader = HistoryReader::open(path("h.sqlite"));
    ASSERT_TRUE(reader.has_value()) << reader.error();
    reader_.emplace(std::move(*reader));
  }
  HistoryReader& reader() { return *reader_; }
  Trace recorded_;
  std::optional<HistoryReader> reader_;
};

TEST_F(Query, ChangesInAClosedTimeRangeInTraceOrder) {
  auto changes = reader().changes(1, {3'000'000, 4'000'000});
  ASSERT_EQ(changes.size(), 4u);
  EXPECT_EQ(changes[0].timeNs, 3'000'000);
  EXPECT_EQ(changes[0].tag, 0u);
  EXPECT_EQ(changes[1].tag, 1u);
  EXPECT_EQ(changes[1].raw, 8u);
  EXPECT_EQ(changes[3].timeNs, 4'000'000);
  EXPECT_EQ(reader().changes(1, {20'000'000, 30'000'000}).size(), 0u);
  EXPECT_EQ(reader().changes(2, {}).size(), 0u);  // no such run
}

TEST_F(Query, ForEachChangeStopsWhenAsked) {
  int seen = 0;
  reader().forEachChange(1, {}, [&](const SignalChange&) { return ++seen < 3; });
  EXPECT_EQ(seen, 3);
}

TEST_F(Query, ValuesBeforeATimeAreTheLastChangesBeforeIt) {
  EXPECT_EQ(reader().valuesBefore(1, 0), (std::vector<uint64_t>{0, 5, 0}));  // the initial values
  EXPECT_EQ(reader().valuesBefore(1, 4'000'000), (std::vector<uint64_t>{1, 8, 0}));
  EXPECT_EQ(reader().valuesBefore(1, 4'000'001), (std::vector<uint64_t>{0, 9, 0}));
}

TEST_F(Query, ActivitiesOverlappingARange) {
  // Strokes 1-3 ms, 4-6 ms, 7-9 ms, 10 ms- (running); the move from 2 ms on, running.
  auto a = reader().activities(1, {5'000'000, 6'500'000});
  ASSERT_EQ(a.size(), 2u);
  EXPECT_EQ(a[0].startNs, 2'000'000);
  EXPECT_EQ(a[0].endNs, -1);
  EXPECT_EQ(a[1].startNs, 4'000'000);
  EXPECT_EQ(a[1].endNs, 6'000'000);
  EXPECT_EQ(reader().activities(1, {9'000'000, 9'000'000}).size(), 2u);  // ends exactly at the start
  EXPECT_EQ(reader().activities(1, {}).size(), 5u);
}

TEST_F(Query, APartOfARunIsShiftedToStartAtZero) {
  Trace t = reader().trace(1, {4'000'000, 8'000'000});
  EXPECT_EQ(t.endNs, 4'000'000);
  EXPECT_EQ(t.signals[1].initial, 8u);  // MAIN.count just before 4 ms
  ASSERT_EQ(t.changes.size(), 10u);     // 4..8 ms, two signals
  EXPECT_EQ(t.changes.front().timeNs, 0);
  EXPECT_EQ(t.changes.back().timeNs, 4'000'000);
  ASSERT_EQ(t.activities.size(), 3u);   // the move (clipped to 0), strokes 4-6 and 7-9 (clipped to 4)
  EXPECT_EQ(t.activities[0].startNs, 0);
  EXPECT_EQ(t.activities[0].endNs, -1);
  EXPECT_EQ(t.activities[2].endNs, 4'000'000);
  ASSERT_EQ(t.collisions.size(), 1u);
  EXPECT_EQ(t.collisions[0].timeNs, 0);
  ASSERT_EQ(t.faults.size(), 1u);
  EXPECT_EQ(t.faults[0].timeNs, 3'000'000);
  EXPECT_EQ(t.cyclesCompleted, 1u);  // the one ending at 5 ms; it began before the range
  EXPECT_EQ(t.cycleEndNs, 0);
  // Totals of a part are its clipped activities': stroke 4-6 ms (9 J) and 7-8 ms of the next.
  EXPECT_EQ(t.totals[0].busyNs, 3'000'000);
  EXPECT_EQ(t.totals[0].energyJ, 9.0 + 13.5);
}

TEST_F(Query, UnknownRunGivesAnEmptyTrace) {
  EXPECT_FALSE(reader().run(7).has_value());
  EXPECT_TRUE(reader().trace(7).signals.empty());
}

// A file whose rows name what the run does not have (edited, or damaged past the integrity
// check): those rows are left out and counted, and every report writer takes the rest.
TEST_F(Query, RowsNamingUnknownSignalsDevicesOrLabelsAreLeftOut) {
  {
    auto db = openDatabase(path("h.sqlite"), OpenMode::Record);
    ASSERT_TRUE(db.has_value());
    ASSERT_TRUE(db->exec("INSERT INTO changes VALUES (1, 5500000, 77, 1);"
                         "INSERT INTO activities VALUES (1, 90, 9, 0, 1, 2, 0, 0), (1, 91, 0, 99, 1, 2, 0, 0);"
                         "INSERT INTO collisions VALUES (1, 5, 1, 2, 0, 1, 0, 50)"));
  }
  auto reader = HistoryReader::open(path("h.sqlite"));
  ASSERT_TRUE(reader.has_value());
  size_t skipped = 0;
  Trace t = reader->trace(1, {}, &skipped);
  EXPECT_EQ(skipped, 4u);
  EXPECT_EQ(t.changes.size(), recorded_.changes.size());
  EXPECT_EQ(t.activities.size(), recorded_.activities.size());
  EXPECT_EQ(t.collisions.size(), 1u);
  report::Kpis kpis = report::computeKpis(t);
  EXPECT_FALSE(report::jsonReport(t, kpis).empty());
  report::HtmlOptions html;
  html.title = "sample";
  html.signals = {"Press.busy", "MAIN.count", "nothing"};
  EXPECT_FALSE(report::htmlReport(t, kpis, html).empty());
  EXPECT_FALSE(report::vcdReport(t).empty());
  EXPECT_FALSE(report::csvChanges(t).empty());
}

}  // namespace
}  // namespace virtcom::history
