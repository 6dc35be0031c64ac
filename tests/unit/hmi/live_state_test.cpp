// The live state over the gearbox cell: what the simulation publishes, commands applied between
// ticks (pause, single step, force, fault), the stations, and the API's answers over it.
#include <gtest/gtest.h>

#include "plc/audited_variables.hpp"
#include "requests.hpp"

#include <cstring>

#include <nlohmann/json.hpp>

#include "hmi/api.hpp"
#include "hmi/live_state.hpp"
#include "sim/simulation.hpp"

namespace virtcom::hmi {
namespace {

using Json = nlohmann::json;

struct GearboxHmi : ::testing::Test {
  SourceManager sources;
  Diagnostics diags;
  std::unique_ptr<cell::Cell> cell;
  std::atomic<bool> interrupt{false};
  std::unique_ptr<LiveState> live;
  std::unique_ptr<sim::Simulation> simulation;
  std::unique_ptr<Api> api;

  void SetUp() override {
    cell = cell::loadCell(std::string(VIRTCOM_SOURCE_DIR) + "/examples/gearbox-cell/cell.yaml", sources, diags);
    ASSERT_TRUE(cell) << diags.render(sources);
    cell->run.cycles = UINT32_MAX;  // as served: cycles are counted, never end the run
    live = std::make_unique<LiveState>(*cell, &interrupt);
    sim::SimOptions options;
    options.speed = 1e6;  // paced (a controlled run always is), but fast
    options.control = live.get();
    options.traceSinks.push_back(live.get());
    options.beforeScan = [this](plc::Runtime& plc) { live->beforeScan(plc); };
    options.afterScan = [this](plc::Runtime& plc) { live->afterScan(plc); };
    simulation = std::make_unique<sim::Simulation>(*cell, options);
    api = std::make_unique<Api>(*cell, *live, simulation->plc().baseTickNs(), WriteAccess{});
  }

  Response call(const Request& r) { return api->handle(parseRequest(r, api->access())); }
  Response postJson(const std::string& path, const std::string& body) { return call(test::post(path, body)); }
  void steps(int n) {
    for (int i = 0; i < n; ++i) ASSERT_TRUE(simulation->step());
  }
  int16_t jobsFinished() {
    auto ref = bc::resolveVariable(*cell->module, "MAIN.jobsFinished");
    int16_t v;
    std::memcpy(&v, simulation->plc().machine().memory() + ref->address, 2);
    return v;
  }
};

TEST_F(GearboxHmi, TheModelListsEveryDeviceWithItsPortsAndPlace) {
  Json model = Json::parse(call(test::get("/api/model")).body);
  ASSERT_EQ(model["devices"].size(), 5u);
  EXPECT_EQ(model["devices"][0]["name"], "Robot1");
  EXPECT_EQ(model["devices"][0]["geometry"]["locations"].size(), 8u);
  EXPECT_GT(model["devices"][0]["place"]["w"].get<double>(), 0);
  EXPECT_EQ(model["baseTickNs"], 10'000'000);
  EXPECT_EQ(model["zones"], Json::array({"SharedTable", "PressArea"}));
}

TEST_F(GearboxHmi, TheModelCarriesTheCellFilesPlacementsAndShapes) {
  Json model = Json::parse(call(test::get("/api/model")).body);
  const Json& robot2 = model["devices"][1];
  EXPECT_EQ(robot2["label"], "Robot2 (IRB 2600)");
  EXPECT_DOUBLE_EQ(robot2["place"]["originX"].get<double>(), 2600) << "hmi: Robot2: base";
  EXPECT_DOUBLE_EQ(robot2["place"]["originY"].get<double>(), 0);
  EXPECT_LT(robot2["place"]["x"].get<double>(), 2600 - 400) << "the box holds the locations around the base";
  const Json& press = model["devices"][2];
  EXPECT_EQ(press["label"], "Servo press");
  EXPECT_EQ(press["place"]["x"], 500);
  EXPECT_EQ(press["place"]["y"], 950);
  EXPECT_EQ(press["place"]["w"], 600);
  EXPECT_EQ(press["place"]["h"], 500);
  EXPECT_EQ(model["devices"][3]["layoutGroup"], "Positioning table");
  EXPECT_EQ(model["devices"][0]["layoutGroup"], "");
  ASSERT_EQ(model["shapes"].size(), 7u);
  EXPECT_EQ(model["shapes"][0], Json({{"kind", "rect"}, {"x", -1000}, {"y", -1100}, {"w", 4800}, {"h", 2700},
                                      {"label", "safety fence"}, {"colour", "#bbbbbb"}}));
  EXPECT_EQ(model["shapes"][3]["r"], 90);
  EXPECT_EQ(model["shapes"][5]["x2"], 3800);
  EXPECT_EQ(model["shapes"][6]["kind"], "text");
}

TEST_F(GearboxHmi, TheFirstFrameHasEverythingThenOnlyChanges) {
  steps(1);
  auto stream = api->openStream(parseRequest(test::get("/api/stream", {{"watch", "MAIN.jobsFinished,MAIN.nothing"}}), {}));
  live->end(simulation->trace());  // publishes now, whatever the wall clock says
  Json first = Json::parse(stream->nextFrame());
  EXPECT_EQ(first["signals"].size(), cell->bus.size());
  EXPECT_EQ(first["unknownWatch"], Json::array({"MAIN.nothing"}));
  EXPECT_EQ(first["vars"][0]["name"], "MAIN.jobsFinished");
  EXPECT_EQ(stream->nextFrame(), "") << "nothing published since";
}

// virtcom monitor with a production plan: the KPIs carry the current shift's parts and plan.
TEST_F(GearboxHmi, TheKpisCarryTheShiftsProgressWhenAPlanIsWatched) {
  steps(1);
  auto stream = api->openStream(parseRequest(test::get("/api/stream"), {}));
  live->end(simulation->trace());
  EXPECT_FALSE(Json::parse(stream->nextFrame())["kpi"].contains("shift")) << "no plan, no shift";
  live->watchShifts([](ShiftProgress& p) {
    p.shift = "Early";
    p.planNow = 12.5;
    p.parts = 3;
  });
  live->end(simulation->trace());  // publishes again
  Json frame = Json::parse(stream->nextFrame());
  EXPECT_EQ(frame["kpi"]["shift"], Json({{"name", "Early"}, {"planNow", 12.5}, {"parts", 3}}));
}

TEST_F(GearboxHmi, PauseHoldsTheRunAndStepAdvancesOneTickAtATime) {
  steps(5);
  const int64_t before = simulation->nowNs();
  EXPECT_EQ(postJson("/api/control", R"({"action": "step", "value": 2})").status, 200);
  steps(2);
  EXPECT_EQ(simulation->nowNs(), before + 2 * 10'000'000);
  interrupt = true;  // paused now: the next tick waits, and an interrupt ends the wait
  EXPECT_FALSE(simulation->step());
  EXPECT_EQ(simulation->nowNs(), before + 2 * 10'000'000);
  EXPECT_EQ(simulation->trace().end, RunEnd::Interrupted);
}

TEST_F(GearboxHmi, AForcedVariableHoldsAgainstTheProgramUntilReleased) {
  steps(1);
  ASSERT_EQ(postJson("/api/write", R"({"name": "main.jobsFinished", "value": "99", "force": true})").status, 200);
  steps(3);
  EXPECT_EQ(jobsFinished(), 99);
  EXPECT_GE(simulation->trace().cyclesCompleted, 1u) << "cycleDone := jobsFinished >= jobCount";
  live->end(simulation->trace());  // publishes now
  Json vars = Json::parse(call(test::get("/api/vars", {{"match", "jobsfinished"}})).body)["vars"];
  EXPECT_EQ(vars[0]["value"], "99");
  EXPECT_EQ(vars[0]["forced"], true);
  ASSERT_EQ(postJson("/api/release", "{}").status, 200);
  ASSERT_EQ(postJson("/api/write", R"({"name": "MAIN.jobsFinished", "value": "0"})").status, 200);
  steps(1);
  EXPECT_LT(jobsFinished(), 99) << "released: the program's value again";
}

// A write and a force from the page are audited as the queues' writes are (docs/security.md):
// the HTTP client's address, the variable, old and new value; the force marked, and written again
// around every scan without a new record.
TEST_F(GearboxHmi, WritesAndForcesFromThePageAreAuditedWithTheClient) {
  std::vector<WriteRecord> records;
  WriteAudit audit(plc::auditedVariables(*cell->module), [&](const WriteRecord& r) { records.push_back(r); });
  live->auditWrites(&audit);
  steps(1);
  const ExternalWriter client{WriteProtocol::Http, 0x0a000009, 51000};
  auto post = [&](const std::string& body) {
    return api->handle(parseRequest(test::post("/api/write", body), api->access()), client).status;
  };
  ASSERT_EQ(post(R"({"name": "MAIN.jobsFinished", "value": "7"})"), 200);
  steps(1);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(formatWriteRecord(records[0]), "http 10.0.0.9:51000 MAIN.jobsFinished: 0 -> 7");
  EXPECT_EQ(records[0].virtualNs, 10'000'000) << "the scan boundary it crossed: the second tick's";
  ASSERT_EQ(post(R"({"name": "MAIN.failed", "value": "TRUE", "force": true})"), 200);
  steps(5);
  ASSERT_EQ(records.size(), 2u) << "the force is written around every scan, audited once";
  EXPECT_EQ(formatWriteRecord(records[1]), "http 10.0.0.9:51000 MAIN.failed: FALSE -> TRUE (forced)");
  EXPECT_EQ(audit.count(WriteProtocol::Http), 2u);
  EXPECT_EQ(audit.total(), 2u);
  EXPECT_EQ(post(R"({"name": "MAIN.nothing", "value": "1"})"), 404);
  steps(1);
  EXPECT_EQ(audit.total(), 2u) << "a refused write is no write";
}

TEST_F(GearboxHmi, BadWritesAreRefusedWithTheReason) {
  EXPECT_EQ(postJson("/api/write", R"({"name": "MAIN.nothing", "value": "1"})").status, 404);
  Response bad = postJson("/api/write", R"({"name": "MAIN.failed", "value": "maybe"})");
  EXPECT_EQ(bad.status, 400);
  EXPECT_NE(bad.body.find("BOOL"), std::string::npos) << bad.body;
  EXPECT_EQ(postJson("/api/write", R"({"name": "MAIN.Robot1", "value": "1"})").status, 400);
  EXPECT_EQ(postJson("/api/fault", R"({"device": "Nobody", "code": 1})").status, 404);
}

TEST_F(GearboxHmi, AnInjectedFaultFailsTheDevicesNextCommand) {
  ASSERT_EQ(postJson("/api/fault", R"({"device": "Robot1", "code": 77})").status, 200);
  for (int i = 0; i < 100 && simulation->step(); ++i) {
  }
  EXPECT_EQ(cell->devices[0]->faults().errorCode, 77);
  EXPECT_EQ(simulation->trace().end, RunEnd::DeviceError);
  EXPECT_EQ(simulation->trace().endMessage, "Robot1 reported error 77");
}


// The stations as published agree with the trace: a station in an operation shows the label and
// start of its device's running activity, an idle one the end of its last; the stream sends a
// station again only when it changed.
TEST_F(GearboxHmi, EachStationShowsItsRunningOperationAndSinceWhen) {
  auto stream = api->openStream(parseRequest(test::get("/api/stream"), {}));
  steps(150);
  live->end(simulation->trace());
  Json first = Json::parse(stream->nextFrame());
  const Trace& trace = simulation->trace();
  ASSERT_EQ(first["stations"].size(), trace.devices.size()) << "the first frame has every station";
  bool someBusy = false;
  for (const Json& s : first["stations"]) {
    const auto device = s[0].get<uint32_t>();
    const ActivityRecord* last = nullptr;
    for (const ActivityRecord& a : trace.activities)
      if (a.device == device) last = &a;
    if (!last) {
      EXPECT_EQ(s, Json::array({device, -1, 0})) << "never busy";
    } else if (last->endNs < 0) {
      someBusy = true;
      EXPECT_EQ(s, Json::array({device, last->label, last->startNs})) << trace.devices[device].name;
    } else {
      EXPECT_EQ(s, Json::array({device, -1, last->endNs})) << trace.devices[device].name;
    }
  }
  EXPECT_TRUE(someBusy) << "1.5 s into the gearbox cycle a station is busy";
  live->end(simulation->trace());
  EXPECT_FALSE(Json::parse(stream->nextFrame()).contains("stations")) << "nothing changed: no stations";
  Json next;
  for (int i = 0; i < 30 && !next.contains("stations"); ++i) {
    steps(100);
    live->end(simulation->trace());
    next = Json::parse(stream->nextFrame());
  }
  ASSERT_TRUE(next.contains("stations")) << "a station changes within 30 s of the gearbox cycle";
  for (const Json& s : next["stations"]) EXPECT_NE(s, first["stations"][s[0].get<size_t>()]) << "only the stations that changed";
}

}  // namespace
}  // namespace virtcom::hmi
