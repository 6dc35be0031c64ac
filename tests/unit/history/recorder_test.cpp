// The recorder: a run recorded tick by tick reads back as the same trace, through the bounded
// queue and the writer thread; a full queue drops events and counts every one.
#include <gtest/gtest.h>

#include "history/query.hpp"
#include "support/allocation_counter.hpp"
#include "history/recorder.hpp"
#include "history/schema.hpp"
#include "history_fixture.hpp"

namespace virtcom::history {
namespace {

using test::HistoryTest;

class Recorder_ : public HistoryTest {
 protected:
  std::unique_ptr<Recorder> open(const std::string& name, RecorderOptions options = {}) {
    options.cellName = "sample";
    options.cellFile = "/cells/sample.yaml";
    options.timeline = {"Press.busy", "MAIN.count"};
    auto recorder = Recorder::open(path(name), std::move(options));
    EXPECT_TRUE(recorder.has_value()) << recorder.error();
    return recorder ? std::move(*recorder) : nullptr;
  }
  HistoryReader read(const std::string& name) {
    auto reader = HistoryReader::open(path(name));
    EXPECT_TRUE(reader.has_value()) << reader.error();
    return std::move(*reader);
  }
};

void expectSameActivities(const ActivityLog& a, const ActivityLog& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].device, b[i].device) << i;
    EXPECT_EQ(a[i].label, b[i].label) << i;
    EXPECT_EQ(a[i].startNs, b[i].startNs) << i;
    EXPECT_EQ(a[i].endNs, b[i].endNs) << i;
    EXPECT_EQ(a[i].energyJ, b[i].energyJ) << i;
    EXPECT_EQ(a[i].errorCode, b[i].errorCode) << i;
  }
}

TEST_F(Recorder_, RoundTripGivesTheTraceBack) {
  auto recorder = open("h.sqlite");
  const Trace recorded = recordSample(*recorder);
  EXPECT_EQ(recorder->drops(), 0u);
  EXPECT_EQ(recorder->error(), "");
  EXPECT_EQ(recorder->runId(), 1);
  recorder.reset();

  HistoryReader reader = read("h.sqlite");
  const Trace t = reader.trace(1);
  ASSERT_EQ(t.signals.size(), recorded.signals.size());
  for (size_t i = 0; i < t.signals.size(); ++i) {
    EXPECT_EQ(t.signals[i].name, recorded.signals[i].name);
    EXPECT_EQ(t.signals[i].type, recorded.signals[i].type);
    EXPECT_EQ(t.signals[i].initial, recorded.signals[i].initial);
  }
  ASSERT_EQ(t.changes.size(), recorded.changes.size());
  for (size_t i = 0; i < t.changes.size(); ++i) {
    EXPECT_EQ(t.changes[i].timeNs, recorded.changes[i].timeNs);
    EXPECT_EQ(t.changes[i].tag, recorded.changes[i].tag);
    EXPECT_EQ(t.changes[i].raw, recorded.changes[i].raw);
  }
  expectSameActivities(t.activities, recorded.activities);
  EXPECT_EQ(t.labels, recorded.labels);
  ASSERT_EQ(t.devices.size(), 2u);
  EXPECT_EQ(t.devices[1].name, "Axis");
  EXPECT_EQ(t.devices[1].type, "axis");
  EXPECT_EQ(t.devices[1].group, "Axes");
  ASSERT_EQ(t.totals.size(), 2u);
  EXPECT_EQ(t.totals[1].busyNs, 8'000'000);
  EXPECT_EQ(t.totals[1].energyJ, 12.25);
  ASSERT_EQ(t.collisions.size(), 1u);
  EXPECT_EQ(t.collisions[0].timeNs, 4'000'000);
  EXPECT_EQ(t.collisions[0].zone, 2u);
  EXPECT_EQ(t.collisions[0].deviceB, 1u);
  EXPECT_EQ(t.collisions[0].activityB, 1u);
  ASSERT_EQ(t.faults.size(), 1u);
  EXPECT_EQ(t.faults[0].timeNs, 7'000'000);
  EXPECT_EQ(t.faults[0].source, "Press");
  EXPECT_EQ(t.faults[0].message, recorded.faults[0].message);  // longer than one text event
  EXPECT_EQ(t.endNs, 10'000'000);
  EXPECT_EQ(t.end, RunEnd::TimeLimit);
  EXPECT_EQ(t.endMessage, "time limit reached");
  EXPECT_EQ(t.cyclesCompleted, 2u);
  EXPECT_EQ(t.cycleStartNs, 5'000'000);
  EXPECT_EQ(t.cycleEndNs, 9'000'000);

  auto run = reader.run(1);
  ASSERT_TRUE(run.has_value());
  EXPECT_EQ(run->cellName, "sample");
  EXPECT_EQ(run->cellFile, "/cells/sample.yaml");
  EXPECT_EQ(run->timeline, (std::vector<std::string>{"Press.busy", "MAIN.count"}));
  EXPECT_TRUE(run->ended);
  EXPECT_EQ(run->endReason, "time limit reached");
  EXPECT_EQ(run->changes, 20);
  EXPECT_EQ(run->activities, 5);
  EXPECT_EQ(run->drops, 0);
  EXPECT_GT(run->wallStartNs, 0);
}

// `virtcom monitor` with a plan: the shifts are written after the run ended and read back.
TEST_F(Recorder_, ProductionPerShiftIsRecordedAfterTheEnd) {
  auto recorder = open("h.sqlite");
  EXPECT_FALSE(recorder->recordProduction({}));  // not begun
  recordSample(*recorder);
  const std::vector<ProductionRow> rows = {{"2026-12-02", "Early", 100, 200, 150, 400, 200.5, 190},
                                           {"2026-12-02", "Late", 200, 300, 200, 320, 10, 12}};
  ASSERT_TRUE(recorder->recordProduction(rows)) << recorder->error();
  recorder.reset();
  HistoryReader reader = read("h.sqlite");
  const std::vector<ProductionRow> back = reader.production(1);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].shift, "Early");
  EXPECT_EQ(back[0].day, "2026-12-02");
  EXPECT_EQ(back[0].startWallNs, 100);
  EXPECT_EQ(back[0].endWallNs, 200);
  EXPECT_EQ(back[0].watchedFromWallNs, 150);
  EXPECT_EQ(back[0].plan, 400);
  EXPECT_DOUBLE_EQ(back[0].planNow, 200.5);
  EXPECT_EQ(back[0].actual, 190);
  EXPECT_EQ(back[1].shift, "Late");
  EXPECT_TRUE(reader.production(2).empty());
}

// `virtcom monitor` with a plan, while recording: each shift occurrence's row as it stands goes
// through the queue and the writer thread; a later row of the same occurrence replaces it; the
// day is the local date the shift started on.
TEST_F(Recorder_, ProductionRowsAreWrittenWhileRecording) {
  RecorderOptions options;
  options.shiftNames = {"Early", "Late"};
  auto recorder = open("h.sqlite", options);
  Trace t = sampleTrace();
  recorder->production(0, {1, 2, 1, 0, 400, 0});  // not begun: nothing to write it into
  recorder->begin(t);
  constexpr int64_t kEarly = 1'796'191'200'000'000'000;  // 2026-12-02 06:00 local
  constexpr int64_t kHourNs = 3'600'000'000'000;
  recorder->production(0, {kEarly, kEarly + 8 * kHourNs, kEarly + kHourNs, 50.0, 400, 3});
  recorder->tick(t, 1'000'000);
  recorder->production(0, {kEarly, kEarly + 8 * kHourNs, kEarly + kHourNs, 62.5, 400, 5});
  recorder->production(1, {kEarly + 8 * kHourNs, kEarly + 16 * kHourNs, kEarly + 8 * kHourNs, 0, 320, 0});
  recorder->production(7, {0, 1, 0, 0, 1, 1});  // not a shift of the plan: left out
  recorder->tick(t, 2'000'000);
  t.endNs = 2'000'000;
  recorder->end(t);
  EXPECT_EQ(recorder->drops(), 0u);
  EXPECT_EQ(recorder->error(), "");
  recorder.reset();
  const std::vector<ProductionRow> back = read("h.sqlite").production(1);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].day, "2026-12-02");
  EXPECT_EQ(back[0].shift, "Early");
  EXPECT_EQ(back[0].startWallNs, kEarly);
  EXPECT_EQ(back[0].watchedFromWallNs, kEarly + kHourNs);
  EXPECT_EQ(back[0].plan, 400);
  EXPECT_DOUBLE_EQ(back[0].planNow, 62.5);
  EXPECT_EQ(back[0].actual, 5) << "the later row replaced the earlier one";
  EXPECT_EQ(back[1].shift, "Late");
  EXPECT_EQ(back[1].day, "2026-12-02");
}

// Audited writes from outside (docs/security.md) are rows of `writes`: times, protocol, peer, the
// ADS client's AmsNetId, variable, location, old and new value, whether forced; long texts whole.
TEST_F(Recorder_, ExternalWritesAreRecordedWithWhoWroteWhat) {
  auto recorder = open("h.sqlite");
  Trace t = sampleTrace();
  recorder->begin(t);
  WriteRecord modbus{120'000'000, 1'796'191'200'123'000'000, {WriteProtocol::Modbus, 0x0a000005, 50123}, "main.speed", "%MW0", "0", "300"};
  WriteRecord ads{2'410'000'000, 1'796'191'202'000'000'000, {WriteProtocol::Ads, 0x7f000001, 40211, true, {192, 168, 1, 7, 1, 1}},
                  "MAIN.name", "", "''", "'" + std::string(200, 'x') + "'"};
  WriteRecord forced{3'000'000'000, 1'796'191'203'000'000'000, {WriteProtocol::Http, 0x7f000001, 8080}, "MAIN.failed", "", "FALSE", "TRUE"};
  forced.writer.force = true;
  recorder->externalWrite(modbus);
  recorder->tick(t, 1'000'000);
  recorder->externalWrite(ads);
  recorder->externalWrite(forced);
  t.endNs = 3'000'000'000;
  recorder->end(t);
  EXPECT_EQ(recorder->drops(), 0u);
  EXPECT_EQ(recorder->error(), "");
  recorder.reset();
  auto db = openDatabase(path("h.sqlite"), OpenMode::Read);
  ASSERT_TRUE(db.has_value()) << db.error();
  Statement rows(*db, "SELECT id, t_ns, wall_ns, protocol, peer, netid, variable, location, old_value, new_value, forced "
                      "FROM writes WHERE run = 1 ORDER BY id");
  std::vector<std::string> got;
  while (rows.step()) {
    std::string row;
    for (int c = 0; c < 11; ++c) row += (c ? "|" : "") + rows.columnText(c);
    got.push_back(row);
  }
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[0], "0|120000000|1796191200123000000|modbus|10.0.0.5:50123||main.speed|%MW0|0|300|0");
  EXPECT_EQ(got[1], "1|2410000000|1796191202000000000|ads|127.0.0.1:40211|192.168.1.7.1.1|MAIN.name||''|'" + std::string(200, 'x') + "'|0");
  EXPECT_EQ(got[2], "2|3000000000|1796191203000000000|http|127.0.0.1:8080||MAIN.failed||FALSE|TRUE|1");
}

TEST_F(Recorder_, RunsAccumulateInOneFile) {
  for (int i = 0; i < 3; ++i) recordSample(*open("h.sqlite"));
  HistoryReader reader = read("h.sqlite");
  auto runs = reader.runs();
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(runs[2].id, 3);
  EXPECT_EQ(reader.lastRunId(), 3);
  EXPECT_EQ(reader.changes(2, {}).size(), 20u);
}

// A queue of one event and a burst of changes within one tick: the writer cannot keep up, and
// every change is either in the database or counted as dropped.
TEST_F(Recorder_, FullQueueDropsAndCountsEveryLostEvent) {
  RecorderOptions options;
  options.queueEvents = 1;
  auto recorder = open("h.sqlite", options);
  Trace t = sampleTrace();
  recorder->begin(t);
  constexpr int kChanges = 5000;
  for (int i = 0; i < kChanges; ++i) recorder->change({1'000'000 + i, 1, static_cast<uint64_t>(i)});
  recorder->tick(t, 1'000'000 + kChanges);
  t.faults.push_back({t.endNs, "PLC", std::string(200, 'f')});  // never fits: dropped at the end too, not waited for
  t.endNs = 1'000'000 + kChanges;
  t.end = RunEnd::Interrupted;
  recorder->end(t);
  EXPECT_GT(recorder->drops(), 0u);
  const uint64_t drops = recorder->drops();
  recorder.reset();
  HistoryReader reader = read("h.sqlite");
  auto run = reader.run(1);
  ASSERT_TRUE(run.has_value());
  EXPECT_EQ(static_cast<uint64_t>(run->drops), drops);
  EXPECT_EQ(static_cast<uint64_t>(run->changes) + drops, static_cast<uint64_t>(kChanges) + 1);  // + the fault
}

TEST_F(Recorder_, WaitWhenFullRecordsEveryEvent) {
  RecorderOptions options;
  options.queueEvents = 1;
  options.waitWhenFull = true;
  auto recorder = open("h.sqlite", options);
  Trace t = sampleTrace();
  recorder->begin(t);
  for (int i = 0; i < 2000; ++i) recorder->change({1'000'000 + i, 1, static_cast<uint64_t>(i)});
  t.faults.push_back({0, "PLC", "short"});  // two events: larger than the queue, so dropped
  t.endNs = 1'000'000 + 2000;
  recorder->end(t);
  EXPECT_EQ(recorder->drops(), 1u);
  recorder.reset();
  EXPECT_EQ(read("h.sqlite").changes(1, {}).size(), 2000u);
}

// A run longer than the trace's window (core/trace_logs.hpp) is recorded whole: the recorder
// takes each activity as it begins and ends, never reads back past the window, and one that runs
// while the window passes it is recorded with its end.
TEST_F(Recorder_, ARunLongerThanTheTraceWindowIsRecordedWhole) {
  RecorderOptions options;
  options.waitWhenFull = true;
  auto recorder = open("h.sqlite", options);
  Trace t = sampleTrace();
  t.setWindow(16);
  recorder->begin(t);
  const uint32_t axis = t.beginActivity(1, 1, 0);  // runs through the whole run
  constexpr int kStrokes = 300;
  for (int k = 1; k <= kStrokes; ++k) {
    const int64_t now = k * 1'000'000;
    t.endActivity(t.beginActivity(0, 0, now), now + 500'000, 0.5, k % 100 == 0 ? 3 : 0);
    if (k == kStrokes) t.endActivity(axis, now, 99);
    recorder->tick(t, now);
  }
  ASSERT_GT(t.activities.elidedCount(), 280u);
  t.endNs = (kStrokes + 1) * 1'000'000LL;
  recorder->end(t);
  EXPECT_EQ(recorder->drops(), 0u);
  recorder.reset();
  const auto recorded = read("h.sqlite").activities(1, {});
  ASSERT_EQ(recorded.size(), kStrokes + 1u);
  EXPECT_EQ(recorded[0].device, 1u);
  EXPECT_EQ(recorded[0].endNs, kStrokes * 1'000'000LL);
  EXPECT_EQ(recorded[0].energyJ, 99);
  for (int k = 1; k <= kStrokes; ++k) {
    EXPECT_EQ(recorded[k].startNs, k * 1'000'000LL) << k;
    EXPECT_EQ(recorded[k].errorCode, k % 100 == 0 ? 3 : 0) << k;
  }
}

// The scan thread's side: no allocation per change or per tick, activities beginning and ending
// included (STYLE rule 7).
TEST_F(Recorder_, RecordingAllocatesNothingPerChangeOrTick) {
  auto recorder = open("h.sqlite");
  Trace t = sampleTrace();
  t.activities.reserve(4096);
  recorder->begin(t);
  size_t allocations = 0;
  {
    virtcom::test::AllocationCounter counter;
    for (int64_t tick = 1; tick <= 2000; ++tick) {
      const int64_t now = tick * 1'000'000;
      recorder->change({now, 0, static_cast<uint64_t>(tick & 1)});
      recorder->change({now, 1, static_cast<uint64_t>(tick)});
      if (tick % 2 == 1) t.beginActivity(0, 0, now);
      else t.endActivity(static_cast<uint32_t>(t.activities.size() - 1), now, 1.0);
      recorder->tick(t, now);
    }
    allocations = counter.count();
  }
  EXPECT_EQ(allocations, 0u);
  t.endNs = 2'000'000'000;
  recorder->end(t);
  EXPECT_EQ(recorder->drops(), 0u);
}

}  // namespace
}  // namespace virtcom::history
