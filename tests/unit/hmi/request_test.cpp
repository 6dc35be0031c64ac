// The HMI's request layer: routes, bodies and write access read from untrusted requests.
#include <gtest/gtest.h>

#include "requests.hpp"

#include "hmi/request.hpp"

namespace virtcom::hmi {
namespace {

using test::get;
using test::post;

TEST(HmiRequest, GetsRouteToThePageModelStreamAndSearch) {
  WriteAccess open;
  EXPECT_EQ(parseRequest(get("/"), open).asset, "index.html");
  EXPECT_EQ(parseRequest(get("/app.js"), open).route, Route::Asset);
  EXPECT_EQ(parseRequest(get(""), open).asset, "index.html") << "found by fuzz_hmi_request";
  EXPECT_EQ(parseRequest(get("/api/model"), open).route, Route::Model);
  ParsedRequest stream = parseRequest(get("/api/stream", {{"watch", "MAIN.a,,GVL.b"}}), open);
  EXPECT_EQ(stream.route, Route::Stream);
  EXPECT_EQ(stream.watch, (std::vector<std::string>{"MAIN.a", "GVL.b"}));
  ParsedRequest vars = parseRequest(get("/api/vars", {{"match", "robot"}}), open);
  EXPECT_EQ(vars.route, Route::Vars);
  EXPECT_EQ(vars.match, "robot");
  EXPECT_EQ(parseRequest(get("/api/nothing"), open).error.status, 404);
}

TEST(HmiRequest, ControlActionsAreChecked) {
  WriteAccess open;
  ParsedRequest speed = parseRequest(post("/api/control", R"({"action": "speed", "value": 2.5})"), open);
  EXPECT_EQ(speed.route, Route::Control);
  EXPECT_EQ(speed.action, Action::Speed);
  EXPECT_DOUBLE_EQ(speed.value, 2.5);
  ParsedRequest step = parseRequest(post("/api/control", R"({"action": "step"})"), open);
  EXPECT_EQ(step.action, Action::Step);
  EXPECT_DOUBLE_EQ(step.value, 1);
  EXPECT_EQ(parseRequest(post("/api/control", R"({"action": "speed", "value": 0})"), open).error.status, 400);
  EXPECT_EQ(parseRequest(post("/api/control", R"({"action": "speed", "value": "fast"})"), open).error.status, 400);
  EXPECT_EQ(parseRequest(post("/api/control", R"({"action": "jump"})"), open).error.status, 400);
  EXPECT_EQ(parseRequest(post("/api/control", "not json"), open).error.status, 400);
  EXPECT_EQ(parseRequest(post("/api/control", "[1]"), open).error.status, 400);
}

TEST(HmiRequest, WritesReleasesAndFaultsNeedTheirFields) {
  WriteAccess open;
  ParsedRequest force = parseRequest(post("/api/write", R"({"name": "MAIN.x", "value": "T#1s", "force": true})"), open);
  EXPECT_EQ(force.route, Route::Write);
  EXPECT_EQ(force.name, "MAIN.x");
  EXPECT_EQ(force.text, "T#1s");
  EXPECT_TRUE(force.force);
  EXPECT_EQ(parseRequest(post("/api/write", R"({"name": "MAIN.x"})"), open).error.status, 400);
  EXPECT_EQ(parseRequest(post("/api/write", R"({"name": "MAIN.x", "value": 1})"), open).error.status, 400);
  EXPECT_EQ(parseRequest(post("/api/write", R"({"name": "MAIN.x", "value": "1", "force": "yes"})"), open).error.status, 400);
  EXPECT_EQ(parseRequest(post("/api/release", "{}"), open).name, "");
  EXPECT_EQ(parseRequest(post("/api/release", R"({"name": "MAIN.x"})"), open).name, "MAIN.x");
  ParsedRequest fault = parseRequest(post("/api/fault", R"({"device": "Press", "code": 50})"), open);
  EXPECT_EQ(fault.route, Route::Fault);
  EXPECT_EQ(fault.code, 50);
  EXPECT_EQ(parseRequest(post("/api/fault", R"({"device": "Press", "code": 1.5})"), open).error.status, 400);
  EXPECT_EQ(parseRequest(post("/api/fault", R"({"device": "Press", "code": 40000})"), open).error.status, 400);
}

TEST(HmiRequest, ReadOnlyRefusesEveryPost) {
  WriteAccess readOnly{true, ""};
  ParsedRequest p = parseRequest(post("/api/control", R"({"action": "pause"})"), readOnly);
  EXPECT_EQ(p.route, Route::Error);
  EXPECT_EQ(p.error.status, 403);
  EXPECT_NE(p.error.body.find("--hmi-readonly"), std::string::npos);
  EXPECT_EQ(parseRequest(get("/api/model"), readOnly).route, Route::Model);
}

TEST(HmiRequest, ATokenIsNeededWhenSet) {
  WriteAccess token{false, "s3cret"};
  const std::string body = R"({"action": "pause"})";
  EXPECT_EQ(parseRequest(post("/api/control", body), token).error.status, 401);
  EXPECT_EQ(parseRequest(post("/api/control", body, "Bearer wrong!"), token).error.status, 401);
  EXPECT_EQ(parseRequest(post("/api/control", body, "s3cret"), token).error.status, 401);
  EXPECT_EQ(parseRequest(post("/api/control", body, "Bearer s3cret"), token).route, Route::Control);
}

TEST(HmiRequest, OtherMethodsAreRefused) {
  EXPECT_EQ(parseRequest(test::request("DELETE", "/api/model"), {}).error.status, 405);
}

TEST(HmiRequest, HistoryRangesAreChecked) {
  const WriteAccess open;
  EXPECT_EQ(parseRequest(get("/api/history/runs"), open).route, Route::HistoryRuns);
  ParsedRequest range = parseRequest(
      get("/api/history/range", {{"run", "2"}, {"from", "1000"}, {"to", "5000"}, {"signals", "Press.busy,,MAIN.x"}, {"points", "50"}}), open);
  ASSERT_EQ(range.route, Route::HistoryRange) << range.error.body;
  EXPECT_EQ(range.run, 2);
  EXPECT_EQ(range.fromNs, 1000);
  EXPECT_EQ(range.toNs, 5000);
  EXPECT_EQ(range.signals, (std::vector<std::string>{"Press.busy", "MAIN.x"}));
  EXPECT_EQ(range.points, 50);
  ParsedRequest whole = parseRequest(get("/api/history/range", {{"run", "1"}}), open);
  EXPECT_EQ(whole.fromNs, 0);
  EXPECT_EQ(whole.toNs, INT64_MAX);
  EXPECT_EQ(whole.points, kDefaultPoints);
  ParsedRequest state = parseRequest(get("/api/history/state", {{"run", "1"}, {"at", "42"}}), open);
  ASSERT_EQ(state.route, Route::HistoryState);
  EXPECT_EQ(state.fromNs, 42);
}

TEST(HmiRequest, BadHistoryParametersSayWhatIsExpected) {
  const WriteAccess open;
  auto refused = [&](std::vector<std::pair<std::string, std::string>> query, const std::string& path = "/api/history/range") {
    ParsedRequest p = parseRequest(get(path, std::move(query)), open);
    EXPECT_EQ(p.route, Route::Error);
    EXPECT_EQ(p.error.status, 400);
    return p.error.body;
  };
  EXPECT_NE(refused({}).find("'run' is missing"), std::string::npos);
  EXPECT_NE(refused({{"run", "0"}}).find("'run' must be a whole number from 1"), std::string::npos);
  EXPECT_NE(refused({{"run", "1x"}}).find("not '1x'"), std::string::npos);
  EXPECT_NE(refused({{"run", "1"}, {"from", "-5"}}).find("'from'"), std::string::npos);
  EXPECT_NE(refused({{"run", "1"}, {"from", "99999999999999999999"}}).find("'from'"), std::string::npos);
  EXPECT_NE(refused({{"run", "1"}, {"from", "10"}, {"to", "5"}}).find("after 'to'"), std::string::npos);
  EXPECT_NE(refused({{"run", "1"}, {"points", "2"}}).find("'points'"), std::string::npos);
  EXPECT_NE(refused({{"run", "1"}, {"points", "20001"}}).find("'points'"), std::string::npos);
  std::string many;
  for (size_t i = 0; i <= kMaxWatch; ++i) many += "s" + std::to_string(i) + ",";
  EXPECT_NE(refused({{"run", "1"}, {"signals", many}}).find("at most"), std::string::npos);
  EXPECT_NE(refused({{"run", "1"}}, "/api/history/state").find("'at' is missing"), std::string::npos);
  EXPECT_EQ(parseRequest(get("/api/history/other"), open).error.status, 404);
}

}  // namespace
}  // namespace virtcom::hmi
