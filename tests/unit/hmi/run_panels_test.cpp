// The live state beyond the gearbox's devices: a reset starting the run again (the snapshot and
// every viewer's stream start over, the run goes on), the active SFC steps of cell-sfc.yaml, the
// fired rules of the tank's activity diagrams, and the parts on the conveyor cell's belt.
#include <gtest/gtest.h>

#include "requests.hpp"

#include <algorithm>
#include <chrono>
#include <set>
#include <thread>

#include <nlohmann/json.hpp>

#include "hmi/api.hpp"
#include "hmi/live_state.hpp"
#include "lang/ad/lower.hpp"
#include "sim/simulation.hpp"

namespace virtcom::hmi {
namespace {

using Json = nlohmann::json;

// One cell under a LiveState and its Api, as `virtcom serve --http` runs it.
struct Served {
  SourceManager sources;
  Diagnostics diags;
  std::string path;
  std::unique_ptr<cell::Cell> cell;
  std::atomic<bool> interrupt{false};
  std::unique_ptr<LiveState> live;
  std::unique_ptr<sim::Simulation> simulation;
  std::unique_ptr<Api> api;

  explicit Served(const std::string& example, std::vector<RuleInfo> rules = {}, std::vector<plc::CountedRule> counted = {})
      : path(std::string(VIRTCOM_SOURCE_DIR) + "/examples/" + example) {
    cell = load();
    live = std::make_unique<LiveState>(*cell, &interrupt);
    live->watchRules(std::move(counted), cell->module ? cell->module->tasks.size() : 0);
    start();
    api = std::make_unique<Api>(*cell, *live, simulation->plc().baseTickNs(), WriteAccess{}, std::move(rules));
  }

  std::unique_ptr<cell::Cell> load() {
    auto c = cell::loadCell(path, sources, diags);
    EXPECT_TRUE(c) << diags.render(sources);
    c->run.until = {};
    c->run.cycles = UINT32_MAX;  // as served: runs until stopped
    return c;
  }

  void start() {
    sim::SimOptions options;
    options.speed = 1e6;  // paced (a controlled run always is), but fast
    options.control = live.get();
    options.traceSinks.push_back(live.get());
    options.beforeScan = [this](plc::Runtime& plc) { live->beforeScan(plc); };
    options.afterScan = [this](plc::Runtime& plc) { live->afterScan(plc); };
    simulation = std::make_unique<sim::Simulation>(*cell, options);
  }

  // What the CLI does after a run that ended on a reset (cli/hmi_options.cpp, reloadForReset):
  // the fresh cell takes over the PLC module object the Api's catalog points at.
  void restart() {
    simulation.reset();
    auto fresh = load();
    fresh->module = std::move(cell->module);
    live->restart(*fresh);
    cell = std::move(fresh);
    start();
  }

  Response post(const std::string& path, const std::string& body) {
    return api->handle(parseRequest(test::post(path, body), api->access()));
  }
  Json model() { return Json::parse(api->handle(parseRequest(test::get("/api/model"), api->access())).body); }
  void steps(int n) {
    for (int i = 0; i < n; ++i) ASSERT_TRUE(simulation->step());
  }
  // Publishes the last tick as the running simulation does: after the publication period of
  // wall time (end() would publish the end time instead).
  void publish() {
    std::this_thread::sleep_for(std::chrono::nanoseconds(LiveState::kPublishPeriodNs + 5'000'000));
    live->tick(simulation->trace(), simulation->nowNs());
  }
};

TEST(HmiReset, TheRunStartsAgainFromTimeZeroAndViewersStartOver) {
  Served s("gearbox-cell/cell.yaml");
  s.steps(300);
  auto stream = s.api->openStream(parseRequest(test::get("/api/stream"), {}));
  s.publish();
  Json before = Json::parse(stream->nextFrame());
  ASSERT_GT(before["t"].get<int64_t>(), 2'000'000'000);
  ASSERT_FALSE(before["activities"].empty());
  EXPECT_FALSE(before.contains("reset"));

  ASSERT_EQ(s.post("/api/control", R"({"action": "reset"})").status, 200);
  EXPECT_FALSE(s.simulation->step()) << "the run ends before the next tick";
  EXPECT_TRUE(s.live->resetting());
  EXPECT_EQ(s.simulation->trace().end, RunEnd::Interrupted);
  EXPECT_EQ(s.simulation->trace().endMessage, "reset");

  s.restart();
  EXPECT_FALSE(s.live->resetting());
  s.steps(10);
  s.publish();
  Json after = Json::parse(stream->nextFrame());
  EXPECT_EQ(after["reset"], 1) << "the viewer is told to clear what it shows";
  EXPECT_LT(after["t"].get<int64_t>(), 200'000'000) << "virtual time starts at 0 again";
  EXPECT_EQ(after["signals"].size(), s.cell->bus.size()) << "everything again, as in a first frame";
  for (const Json& a : after["activities"]) EXPECT_LT(a[3].get<int64_t>(), 100'000'000) << a.dump();
  EXPECT_EQ(after["kpi"]["cycles"], 0);
  s.live->read([](const Snapshot& snap) {
    EXPECT_EQ(snap.run, 1u);
    EXPECT_TRUE(snap.faults.empty());
  });
  s.steps(300);
  EXPECT_GT(s.simulation->nowNs(), 3'000'000'000) << "the new run goes on";
}

TEST(HmiReset, AResetEndsThePausedWaitAndTheNewRunStartsPaused) {
  Served s("gearbox-cell/cell.yaml");
  s.steps(5);
  ASSERT_EQ(s.post("/api/control", R"({"action": "pause"})").status, 200);
  // Whether the reset arrives before or during the paused wait, the run ends on it.
  std::thread viewer([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    s.post("/api/control", R"({"action": "reset"})");
  });
  EXPECT_FALSE(s.simulation->step());
  viewer.join();
  EXPECT_EQ(s.simulation->trace().endMessage, "reset");
  s.restart();
  ASSERT_EQ(s.post("/api/control", R"({"action": "step", "value": 3})").status, 200);
  s.steps(3);
  EXPECT_EQ(s.simulation->nowNs(), 2 * 10'000'000) << "three ticks from 0, one at a time";
  s.publish();
  s.live->read([](const Snapshot& snap) { EXPECT_TRUE(snap.paused); });
}

TEST(HmiReset, AResetAfterTheEndIsTakenOnceAndOtherCommandsBeforeItAreDropped) {
  Served s("gearbox-cell/cell.yaml");
  EXPECT_FALSE(s.live->takeReset());
  ASSERT_EQ(s.post("/api/control", R"({"action": "pause"})").status, 200);
  ASSERT_EQ(s.post("/api/control", R"({"action": "reset"})").status, 200);
  EXPECT_TRUE(s.live->takeReset());
  EXPECT_FALSE(s.live->takeReset());
  s.steps(1);  // not paused: the pause before the reset was dropped with it
}

TEST(HmiReset, ARefusedResetAnswers409WithTheReason) {
  Served s("gearbox-cell/cell.yaml");
  s.api->refuseReset("reset is off while --modbus or --ads serve the run");
  Response r = s.post("/api/control", R"({"action": "reset"})");
  EXPECT_EQ(r.status, 409);
  EXPECT_NE(r.body.find("--modbus or --ads"), std::string::npos) << r.body;
  s.steps(2);
  EXPECT_FALSE(s.live->resetting());
}

TEST(HmiPanels, TheSfcPanelShowsTheActiveStepAndItsTime) {
  Served s("gearbox-cell/cell-sfc.yaml");
  Json steps = s.model()["sfcSteps"];
  ASSERT_FALSE(steps.empty());
  EXPECT_NE(std::ranges::find(steps, Json("MAIN.Load")), steps.end()) << steps.dump();
  auto stream = s.api->openStream(parseRequest(test::get("/api/stream"), {}));
  s.steps(1);
  s.publish();
  Json first = Json::parse(stream->nextFrame());
  ASSERT_TRUE(first.contains("steps"));
  ASSERT_FALSE(first["steps"].empty());
  const Json initial = first["steps"];
  std::set<std::string> seen;
  for (int i = 0; i < 100 && seen.size() < 3; ++i) {
    s.steps(20);
    s.publish();
    Json f = Json::parse(stream->nextFrame());
    if (!f.contains("steps")) continue;
    for (const Json& active : f["steps"]) {
      seen.insert(steps[active[0].get<size_t>()].get<std::string>());
      EXPECT_GE(active[1].get<int32_t>(), 0);
    }
  }
  EXPECT_GE(seen.size(), 3u) << "the active steps change as the chart runs";
}

// The tank's rules, with their fired flags resolved as the CLI does (cli/rule_trace.hpp).
TEST(HmiPanels, TheRulePanelCountsEveryScanWhoseIfHeld) {
  std::vector<RuleInfo> rules;
  std::vector<plc::CountedRule> flags;
  {
    SourceManager sources;
    Diagnostics diags;
    auto cell = cell::loadCell(std::string(VIRTCOM_SOURCE_DIR) + "/examples/activity/tank-cell.yaml", sources, diags);
    ASSERT_TRUE(cell) << diags.render(sources);
    for (int k = 1;; ++k) {
      auto ref = bc::resolveVariable(*cell->module, "TankControl." + std::string(ad::kFiredVariable) + "[" + std::to_string(k) + "]");
      if (!ref) break;
      rules.push_back({"Tank", std::to_string(k), "1", "then " + std::to_string(k)});
      flags.push_back({*ref, 0});  // the tank cell's one task
    }
  }
  ASSERT_GT(flags.size(), 3u);
  Served s("activity/tank-cell.yaml", rules, flags);
  EXPECT_EQ(s.model()["rules"].size(), rules.size());
  EXPECT_EQ(s.model()["rules"][1]["index"], "2");
  auto stream = s.api->openStream(parseRequest(test::get("/api/stream"), {}));
  s.steps(500);
  s.publish();
  Json frame = Json::parse(stream->nextFrame());
  ASSERT_EQ(frame["rules"].size(), rules.size()) << "the first frame lists every rule";
  uint64_t fired = 0;
  for (const Json& r : frame["rules"]) {
    const uint64_t count = r[1];
    fired += count;
    EXPECT_LE(count, 500u);
    if (count > 0) EXPECT_GE(r[2].get<int64_t>(), 0) << "fired: it has a last time";
    else EXPECT_EQ(r[2], -1);
  }
  EXPECT_GT(fired, 0u);
  s.steps(100);
  s.publish();
  Json next = Json::parse(stream->nextFrame());
  if (next.contains("rules")) {
    EXPECT_LT(next["rules"].size(), rules.size()) << "only the rules that fired since";
  }
}

TEST(HmiPanels, PartsMoveAlongTheConveyorsBelt) {
  Served s("activity/conveyor-cell.yaml");
  const Json belt = s.model()["devices"][2];
  ASSERT_EQ(belt["type"], "conveyor");
  EXPECT_EQ(belt["geometry"]["pushers"].size(), 2u);
  EXPECT_EQ(belt["geometry"]["kinds"][0], "steel");
  EXPECT_EQ(belt["geometry"]["discharge"], true);
  EXPECT_DOUBLE_EQ(belt["geometry"]["partLength"].get<double>(), 100);
  auto stream = s.api->openStream(parseRequest(test::get("/api/stream"), {}));
  s.steps(300);  // 3 s: the first part is on the belt
  s.publish();
  Json frame = Json::parse(stream->nextFrame());
  ASSERT_EQ(frame["belts"].size(), 1u);
  EXPECT_EQ(frame["belts"][0]["device"], 2);
  // [position mm, kind], the newest part (nearest the start) first
  auto lead = [](const Json& parts) { return *std::ranges::max_element(parts, {}, [](const Json& p) { return p[0].get<int32_t>(); }); };
  const Json parts = frame["belts"][0]["parts"];
  ASSERT_GE(parts.size(), 2u) << "a part every 2 s";
  EXPECT_EQ(lead(parts)[1], 0) << "the first part is steel";
  EXPECT_GT(lead(parts)[0].get<int32_t>(), 300);
  s.steps(100);
  s.publish();
  Json later = Json::parse(stream->nextFrame());
  ASSERT_EQ(later["belts"].size(), 1u) << "the parts moved";
  EXPECT_GT(lead(later["belts"][0]["parts"])[0].get<int32_t>(), lead(parts)[0].get<int32_t>());
}

}  // namespace
}  // namespace virtcom::hmi
