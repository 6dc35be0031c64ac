// Retention: the oldest runs, and all their rows, go beyond an age or a file size; the run being
// recorded never does.
#include <gtest/gtest.h>

#include "history/query.hpp"
#include "history/recorder.hpp"
#include "history/retention.hpp"
#include "history/schema.hpp"
#include "history_fixture.hpp"

namespace virtcom::history {
namespace {

class Retention : public test::HistoryTest {
 protected:
  void recordRun(RecorderOptions options = {}) {
    auto recorder = Recorder::open(path("h.sqlite"), std::move(options));
    ASSERT_TRUE(recorder.has_value()) << recorder.error();
    pruned_ = (*recorder)->pruned();
    recordSample(**recorder);
  }
  int64_t pruned_ = 0;
};

TEST_F(Retention, ByAgeDeletesOldRunsWhenOpened) {
  for (int i = 0; i < 2; ++i) recordRun();
  {
    auto db = openDatabase(path("h.sqlite"), OpenMode::Record);
    ASSERT_TRUE(db.has_value());
    ASSERT_TRUE(db->exec("UPDATE runs SET wall_start_ns = wall_start_ns - 3 * 86400000000000 WHERE id = 1"));
  }
  RecorderOptions options;
  options.retention.keepDays = 2;
  recordRun(options);
  EXPECT_EQ(pruned_, 1);
  auto reader = HistoryReader::open(path("h.sqlite"));
  ASSERT_TRUE(reader.has_value());
  auto runs = reader->runs();
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].id, 2);
  EXPECT_EQ(reader->changes(1, {}).size(), 0u);  // its rows went with it
  EXPECT_EQ(reader->activities(1, {}).size(), 0u);
  EXPECT_EQ(reader->signals(1).size(), 0u);
}

TEST_F(Retention, BySizeKeepsTheNewestRuns) {
  for (int i = 0; i < 4; ++i) recordRun();
  auto db = openDatabase(path("h.sqlite"), OpenMode::Record);
  ASSERT_TRUE(db.has_value());
  EXPECT_EQ(pruneRuns(*db, {0, usedBytes(*db)}, 4, 0), 0);  // within the limit
  EXPECT_EQ(pruneRuns(*db, {0, 1}, 4, 0), 3);  // oldest first, all but the current run
  int64_t runs = 0;
  ASSERT_TRUE(db->queryInt("SELECT MIN(id) + COUNT(*) * 10 FROM runs", runs));
  EXPECT_EQ(runs, 14);  // run 4 alone
}

}  // namespace
}  // namespace virtcom::history
