// The HMI's history routes over a recorded gearbox run: the runs, a range's activities (the Gantt
// chart's rows) and decimated signals (the trends), the state at a time, and their refusals.
#include <gtest/gtest.h>

#include "requests.hpp"
#include <unistd.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "history/recorder.hpp"
#include "hmi/api.hpp"
#include "hmi/history_api.hpp"
#include "sim/simulation.hpp"

namespace virtcom::hmi {
namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

constexpr int64_t kRunNs = 20'000'000'000;

// One gearbox run of 20 s virtual time recorded into a fresh file, shared by the tests; the
// run's trace (everything kept) is what the answers are compared with.
class HistoryApiTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    path_ = (fs::temp_directory_path() / ("virtcom-hmi-history-" + std::to_string(::getpid()) + ".sqlite")).string();
    fs::remove(path_);
    cell_ = cell::loadCell(std::string(VIRTCOM_SOURCE_DIR) + "/examples/gearbox-cell/cell.yaml", sources_, diags_);
    ASSERT_TRUE(cell_) << diags_.render(sources_);
    history::RecorderOptions recording;
    recording.cellName = cell_->name;
    recording.waitWhenFull = true;
    auto recorder = history::Recorder::open(path_, recording);
    ASSERT_TRUE(recorder.has_value()) << recorder.error();
    sim::SimOptions options;
    options.timeLimitNs = kRunNs;
    options.traceSinks.push_back(recorder->get());
    sim::Simulation simulation(*cell_, options);
    simulation.run();
    trace_ = cell_->trace;
  }
  static void TearDownTestSuite() {
    fs::remove(path_);
    cell_.reset();
  }
  void SetUp() override {
    auto api = HistoryApi::open(path_);
    ASSERT_TRUE(api.has_value()) << api.error();
    api_ = std::move(*api);
  }

  Response get(const std::string& path, std::vector<std::pair<std::string, std::string>> query = {}) {
    return api_->handle(parseRequest(test::get(path, std::move(query)), {}));
  }
  Json getJson(const std::string& path, std::vector<std::pair<std::string, std::string>> query = {}) {
    Response r = get(path, std::move(query));
    EXPECT_EQ(r.status, 200) << r.body;
    return Json::parse(r.body);
  }
  // The activities of the run's trace overlapping [from, to], as the API must list them.
  static size_t overlapping(int64_t from, int64_t to) {
    size_t n = 0;
    for (const ActivityRecord& a : trace_.activities) n += a.startNs <= to && (a.endNs < 0 || a.endNs >= from);
    return n;
  }

  static inline std::string path_;
  static inline SourceManager sources_;
  static inline Diagnostics diags_;
  static inline std::unique_ptr<cell::Cell> cell_;
  static inline Trace trace_;
  std::unique_ptr<HistoryApi> api_;
};

TEST_F(HistoryApiTest, ListsTheRecordedRun) {
  Json runs = getJson("/api/history/runs")["runs"];
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0]["id"], 1);
  EXPECT_EQ(runs[0]["cell"], cell_->name);
  EXPECT_EQ(runs[0]["activities"].get<size_t>(), trace_.activities.size());
  EXPECT_EQ(runs[0]["endNs"].get<int64_t>(), trace_.endNs);
}

TEST_F(HistoryApiTest, ARangeHasTheActivitiesOverlappingIt) {
  ASSERT_GT(trace_.activities.size(), 10u);
  Json whole = getJson("/api/history/range", {{"run", "1"}});
  EXPECT_EQ(whole["activities"].size(), trace_.activities.size());
  EXPECT_EQ(whole["devices"].size(), trace_.devices.size());
  EXPECT_EQ(whole["to"].get<int64_t>(), trace_.endNs);
  Json part = getJson("/api/history/range", {{"run", "1"}, {"from", "5000000000"}, {"to", "8000000000"}});
  EXPECT_EQ(part["activities"].size(), overlapping(5'000'000'000, 8'000'000'000));
  EXPECT_LT(part["activities"].size(), whole["activities"].size());
  for (const Json& a : part["activities"]) {
    EXPECT_LE(a[3].get<int64_t>(), 8'000'000'000);
    EXPECT_TRUE(a[4].get<int64_t>() < 0 || a[4].get<int64_t>() >= 5'000'000'000);
  }
}

TEST_F(HistoryApiTest, SignalsComeWithTheValueBeforeTheRangeAndDecimated) {
  // The signal that changes most often in the run.
  std::vector<size_t> counts(trace_.signals.size());
  for (const SignalChange& c : trace_.changes) ++counts[c.tag];
  const size_t busiest = static_cast<size_t>(std::ranges::max_element(counts) - counts.begin());
  const std::string name = trace_.signals[busiest].name;
  ASSERT_GT(counts[busiest], 60u) << name;
  Json all = getJson("/api/history/range", {{"run", "1"}, {"signals", name}, {"points", "20000"}});
  ASSERT_EQ(all["series"].size(), 1u);
  EXPECT_EQ(all["series"][0]["points"].size(), counts[busiest]);
  EXPECT_FALSE(all["series"][0]["decimated"].get<bool>());
  Json few = getJson("/api/history/range", {{"run", "1"}, {"signals", name}, {"points", "30"}});
  const Json& s = few["series"][0];
  EXPECT_TRUE(s["decimated"].get<bool>());
  EXPECT_EQ(s["changes"].get<size_t>(), counts[busiest]);
  EXPECT_LE(s["points"].size(), 30u);
  EXPECT_GE(s["points"].size(), 2u);
  // The last point is the run's last change of the signal: the value held at the end is right.
  EXPECT_EQ(s["points"].back(), all["series"][0]["points"].back());
}

TEST_F(HistoryApiTest, TheStateAtATimeHasTheValuesAndRunningActivities) {
  const int64_t at = 10'000'000'000;
  Json state = getJson("/api/history/state", {{"run", "1"}, {"at", std::to_string(at)}});
  size_t running = 0;
  for (const ActivityRecord& a : trace_.activities) running += a.startNs <= at && (a.endNs < 0 || a.endNs > at);
  EXPECT_EQ(state["activities"].size(), running);
  EXPECT_EQ(state["values"].size(), trace_.signals.size());
}

TEST_F(HistoryApiTest, BadRunsAndSignalsAreRefusedClearly) {
  Response noRun = get("/api/history/range", {{"run", "9"}});
  EXPECT_EQ(noRun.status, 404);
  EXPECT_NE(noRun.body.find("no run 9"), std::string::npos);
  Response noSignal = get("/api/history/range", {{"run", "1"}, {"signals", "Nothing.here"}});
  EXPECT_EQ(noSignal.status, 400);
  EXPECT_NE(noSignal.body.find("Nothing.here"), std::string::npos);
}

TEST_F(HistoryApiTest, TheLiveApiAnswersHistoryOnlyWhenGivenOne) {
  LiveState live(*cell_, nullptr);
  Api page(*cell_, live, cell_->run.plcCycleNs, {});
  ParsedRequest runs = parseRequest(test::get("/api/history/runs"), {});
  EXPECT_EQ(page.handle(runs).status, 404);
  EXPECT_FALSE(Json::parse(page.handle(parseRequest(test::get("/api/model"), {})).body)["history"].get<bool>());
  page.attachHistory(*api_, true);
  EXPECT_EQ(page.handle(runs).status, 200);
  Json model = Json::parse(page.handle(parseRequest(test::get("/api/model"), {})).body);
  EXPECT_TRUE(model["history"].get<bool>());
  EXPECT_TRUE(model["replay"].get<bool>());
}

}  // namespace
}  // namespace virtcom::hmi
