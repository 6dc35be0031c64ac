// End-to-end: the web HMI of the gearbox cell in real Chromium (tests/e2e/hmi/check_hmi.js, npm
// playwright-core driving Debian's chromium; `make test` installs it with npm ci):
//  - `virtcom serve cell.yaml --http`: every device drawn, a robot moves, the Gantt grows, two
//    browsers at once, one killed mid-run, pause and single step, a forced variable changes the
//    PLC; screenshots in the test's output directory (artifacts);
//  - `virtcom run cell.yaml --hmi`: the page follows a paced run to its end;
//  - Reset (served, and after a run's end; refused with --modbus), the SFC step panel
//    (cell-sfc.yaml), the fired-rule panel (activity/tank-cell.yaml) and parts on a conveyor
//    (activity/conveyor-cell.yaml): tests/e2e/hmi/check_run_panels.js;
//  - the Stations panel (tests/e2e/hmi/check_stations.js) on `run --hmi` and on `monitor --http`
//    watching a served cell;
//  - the History panel: a recorded run browsed with `virtcom history --http`, the past of a
//    served run (tests/e2e/hmi/check_history.js);
//  - the start-up checks of the HMI options.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "server_process.hpp"
#include "shell_command.hpp"
#include "support/read_file.hpp"

namespace {

namespace fs = std::filesystem;
using virtcom::e2e::ServerProcess;
using virtcom::e2e::shell;

const std::string kExe = VIRTCOM_EXE;
const std::string kGearbox = std::string(VIRTCOM_SOURCE_DIR) + "/examples/gearbox-cell";
const std::string kActivity = std::string(VIRTCOM_SOURCE_DIR) + "/examples/activity";
const std::string kClientDir = VIRTCOM_HMI_CLIENT_DIR;
const std::string kAnnounce = "hmi: serving http://";
constexpr const char* kChromium = "/usr/bin/chromium";

// The screenshots' directory: kept after the test (build/.../hmi-artifacts/<test>).
std::string artifactDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  fs::path dir = fs::current_path() / "hmi-artifacts" / info->name();
  fs::create_directories(dir);
  return dir.string();
}

// Skips (or, with VIRTCOM_REQUIRE_BROWSER=1 as `make test` sets, fails) without the browser.
bool browserMissing() {
  if (::access(kChromium, X_OK) == 0 && fs::exists(kClientDir + "/node_modules/playwright-core")) return false;
  const char* require = std::getenv("VIRTCOM_REQUIRE_BROWSER");
  if (require != nullptr && std::string(require) == "1")
    ADD_FAILURE() << kChromium << " or npm playwright-core is missing: install chromium and run `npm ci --prefix tests/e2e/hmi`";
  return true;
}

int runCheck(const std::string& mode, int port, std::string& out, const std::string& script = "check_hmi.js") {
  return shell("cd '" + kClientDir + "' && node " + script + " " + mode + " " + std::to_string(port) + " '" + artifactDir() + "'", out);
}

// `virtcom serve CELL --http 127.0.0.1:0 ARGS...` in `dir`, checked by check_run_panels.js MODE.
void checkServedPanels(const std::string& dir, const std::string& cellFile, const std::string& mode, std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"serve", dir + "/" + cellFile, "--http", "127.0.0.1:0", "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  ServerProcess cell(kExe, args, dir, kAnnounce);
  ASSERT_GT(cell.port(), 0) << cell.errorOutput();
  std::string out;
  EXPECT_EQ(runCheck(mode, cell.port(), out, "check_run_panels.js"), 0) << out << cell.errorOutput();
  EXPECT_NE(out.find("hmi checks passed"), std::string::npos) << out;
  EXPECT_EQ(cell.stop(), 0) << cell.errorOutput();
}

TEST(Hmi, TheServedGearboxCellIsWatchedAndSteeredFromTwoBrowsers) {
  if (browserMissing()) GTEST_SKIP() << "no browser";
  ServerProcess cell(kExe, {"serve", kGearbox + "/cell.yaml", "--http", "127.0.0.1:0", "--quiet"}, kGearbox, kAnnounce);
  ASSERT_GT(cell.port(), 0) << cell.errorOutput();
  std::string out;
  EXPECT_EQ(runCheck("served", cell.port(), out), 0) << out;
  EXPECT_NE(out.find("hmi checks passed"), std::string::npos) << out;
  EXPECT_EQ(cell.stop(), 0) << cell.errorOutput();
}

TEST(Hmi, APacedRunIsFollowedToItsEnd) {
  if (browserMissing()) GTEST_SKIP() << "no browser";
  ServerProcess run(kExe, {"run", kGearbox + "/cell.yaml", "--hmi", "127.0.0.1:0", "--speed", "20", "--quiet"}, kGearbox, kAnnounce);
  ASSERT_GT(run.port(), 0) << run.errorOutput();
  std::string out;
  EXPECT_EQ(runCheck("ended", run.port(), out), 0) << out;
  EXPECT_NE(out.find("hmi checks passed"), std::string::npos) << out;
  EXPECT_EQ(run.stop(), 0) << run.errorOutput();
  EXPECT_NE(run.errorOutput().find("the run has ended"), std::string::npos) << run.errorOutput();
}

TEST(Hmi, ResetStartsTheServedRunAgainAndThePageFollows) {
  if (browserMissing()) GTEST_SKIP() << "no browser";
  checkServedPanels(kGearbox, "cell.yaml", "reset", {"--speed", "4"});
}

TEST(Hmi, ResetIsRefusedWhileModbusServesTheRun) {
  if (browserMissing()) GTEST_SKIP() << "no browser";
  checkServedPanels(kGearbox, "cell.yaml", "refused", {"--modbus", "127.0.0.1:0"});
}

TEST(Hmi, TheSfcPanelFollowsTheActiveSteps) {
  if (browserMissing()) GTEST_SKIP() << "no browser";
  checkServedPanels(kGearbox, "cell-sfc.yaml", "sfc", {"--speed", "4"});
}

TEST(Hmi, TheRulePanelCountsTheTanksFiredRules) {
  if (browserMissing()) GTEST_SKIP() << "no browser";
  checkServedPanels(kActivity, "tank-cell.yaml", "rules", {"--speed", "4"});
}

TEST(Hmi, PartsAreDrawnOnTheConveyorAndBinsCountThem) {
  if (browserMissing()) GTEST_SKIP() << "no browser";
  checkServedPanels(kActivity, "conveyor-cell.yaml", "parts", {"--speed", "2", "--hmi-paused"});
}

TEST(Hmi, AResetAfterTheEndOfARunStartsItAgain) {
  if (browserMissing()) GTEST_SKIP() << "no browser";
  ServerProcess run(kExe, {"run", kGearbox + "/cell.yaml", "--hmi", "127.0.0.1:0", "--speed", "5", "--quiet"}, kGearbox, kAnnounce);
  ASSERT_GT(run.port(), 0) << run.errorOutput();
  std::string out;
  EXPECT_EQ(runCheck("reset-ended", run.port(), out, "check_run_panels.js"), 0) << out << run.errorOutput();
  EXPECT_EQ(run.stop(), 0) << run.errorOutput();
  EXPECT_NE(run.errorOutput().find("hmi: reset: the run starts again"), std::string::npos) << run.errorOutput();
}

// With --history, each reset ends the recorded run and starts a new one (no browser needed: the
// write and the reset are POSTed by node). A write before the reset belongs to the run that
// ended: the new run's report counts only its own (as its history does), while the command's
// audit summary counts every write it audited (the new run's report counted the old run's writes
// too before they went into the run's trace).
TEST(Hmi, EveryResetStartsANewRecordedRun) {
  const std::string tmp = (fs::temp_directory_path() / ("virtcom-hmi-reset-" + std::to_string(::getpid()))).string();
  const std::string db = tmp + ".sqlite", json = tmp + ".json";
  fs::remove(db);
  ServerProcess cell(kExe, {"serve", kGearbox + "/cell.yaml", "--http", "127.0.0.1:0", "--quiet", "--history", db, "--json", json},
                     kGearbox, kAnnounce);
  ASSERT_GT(cell.port(), 0) << cell.errorOutput();
  const std::string api = "http://127.0.0.1:" + std::to_string(cell.port()) + "/api/";
  const std::string writeThenReset =
      "node -e \"const post = (p, b) => fetch('" + api + "' + p, {method: 'POST', body: JSON.stringify(b)}).then((r) => r.status);"
      " (async () => { const w = await post('write', {name: 'MAIN.jobCount', value: '7'});"
      " const r = await post('control', {action: 'reset'}); process.exit(w === 200 && r === 200 ? 0 : 1); })()\"";
  std::string out;
  ASSERT_EQ(shell(writeThenReset, out), 0) << out;
  ASSERT_TRUE(cell.waitFor("hmi: reset: the run starts again")) << cell.errorOutput();
  EXPECT_EQ(cell.stop(), 0) << cell.errorOutput();
  const std::string log = cell.errorOutput();
  EXPECT_NE(log.find("history: run 1 recorded"), std::string::npos) << log;
  EXPECT_NE(log.find("history: run 2 recorded"), std::string::npos) << log;
  EXPECT_NE(log.find("audit: 1 external writes (ads 0, modbus 0, opcua 0, http 1)"), std::string::npos) << log;
  const std::string report = virtcom::test::readFile(json);
  EXPECT_NE(report.find("\"external_writes\": {\n      \"total\": 0,"), std::string::npos) << report;
  out.clear();
  ASSERT_EQ(shell(kExe + " history '" + db + "'", out), 0) << out;
  EXPECT_NE(out.find("\n2 "), std::string::npos) << "two runs listed: " << out;
  out.clear();
  ASSERT_EQ(shell(kExe + " history '" + db + "' --run 1 --writes", out), 0) << out;
  EXPECT_NE(out.find(" MAIN.jobCount: "), std::string::npos) << "the write in run 1: " << out;
  fs::remove(db);
  fs::remove(json);
}

// The Stations panel (each station's state, operation and elapsed time, tests/e2e/hmi/
// check_stations.js) agrees with the Gantt chart on a paced run and on a monitor of a served cell.
TEST(Hmi, TheStationsPanelShowsEachStationsOperationAndElapsedTimeInARun) {
  if (browserMissing()) GTEST_SKIP() << "no browser";
  ServerProcess run(kExe, {"run", kGearbox + "/cell.yaml", "--hmi", "127.0.0.1:0", "--speed", "2", "--quiet"}, kGearbox, kAnnounce);
  ASSERT_GT(run.port(), 0) << run.errorOutput();
  std::string out;
  EXPECT_EQ(runCheck("live", run.port(), out, "check_stations.js"), 0) << out << run.errorOutput();
  EXPECT_NE(out.find("hmi checks passed"), std::string::npos) << out;
  EXPECT_EQ(run.stop(), 3) << "stopped in the middle of the run (RunStopped): " << run.errorOutput();
}

TEST(Hmi, TheStationsPanelShowsTheWatchedPlantsStationsInAMonitor) {
  if (browserMissing()) GTEST_SKIP() << "no browser";
  const std::string adsCell = std::string(VIRTCOM_SOURCE_DIR) + "/examples/ads-cell";
  ServerProcess plant(kExe, {"serve", adsCell + "/cell.yaml", "--ads", "127.0.0.1:0", "--quiet"}, adsCell, "ads: serving on ");
  ASSERT_GT(plant.port(), 0) << plant.errorOutput();
  ServerProcess monitor(kExe,
                        {"monitor", adsCell + "/cell.yaml", "--ads", "127.0.0.1:" + std::to_string(plant.port()), "--poll", "5ms",
                         "--http", "127.0.0.1:0", "--quiet"},
                        adsCell, kAnnounce);
  ASSERT_GT(monitor.port(), 0) << monitor.errorOutput();
  std::string out;
  EXPECT_EQ(runCheck("live", monitor.port(), out, "check_stations.js"), 0) << out << monitor.errorOutput();
  EXPECT_NE(out.find("hmi checks passed"), std::string::npos) << out;
  EXPECT_EQ(monitor.stop(), 0) << monitor.errorOutput();
  EXPECT_EQ(plant.stop(), 0) << plant.errorOutput();
}

// The History panel (tests/e2e/hmi/check_history.js): a recorded run browsed with `virtcom
// history FILE --http` (its Gantt chart, a trend, a zoomed range, the layout at a time), and the
// past of a served run shown while it runs (`serve --history --http`).
TEST(Hmi, ARecordedRunIsBrowsedFromItsHistory) {
  if (browserMissing()) GTEST_SKIP() << "no browser";
  const std::string db = (fs::temp_directory_path() / ("virtcom-hmi-browse-" + std::to_string(::getpid()) + ".sqlite")).string();
  fs::remove(db);
  std::string out;
  ASSERT_EQ(shell(kExe + " run '" + kGearbox + "/cell.yaml' --quiet --history '" + db + "'", out), 0) << out;
  {
    ServerProcess browse(kExe, {"history", db, "--http", "127.0.0.1:0"}, kGearbox, kAnnounce);
    ASSERT_GT(browse.port(), 0) << browse.errorOutput();
    EXPECT_EQ(runCheck("replay", browse.port(), out, "check_history.js"), 0) << out << browse.errorOutput();
    EXPECT_NE(out.find("hmi checks passed"), std::string::npos) << out;
    EXPECT_EQ(browse.stop(), 0) << browse.errorOutput();
  }
  fs::remove(db);
}

TEST(Hmi, ThePastOfTheServedRunIsShownFromItsHistory) {
  if (browserMissing()) GTEST_SKIP() << "no browser";
  const std::string db = (fs::temp_directory_path() / ("virtcom-hmi-past-" + std::to_string(::getpid()) + ".sqlite")).string();
  fs::remove(db);
  {
    ServerProcess cell(kExe, {"serve", kGearbox + "/cell.yaml", "--http", "127.0.0.1:0", "--quiet", "--speed", "4", "--history", db},
                       kGearbox, kAnnounce);
    ASSERT_GT(cell.port(), 0) << cell.errorOutput();
    std::string out;
    EXPECT_EQ(runCheck("live", cell.port(), out, "check_history.js"), 0) << out << cell.errorOutput();
    EXPECT_NE(out.find("hmi checks passed"), std::string::npos) << out;
    EXPECT_EQ(cell.stop(), 0) << cell.errorOutput();
  }
  fs::remove(db);
}

// monitor --history --http: the page's history routes read the file the monitor records (no
// browser needed: node asks the API).
TEST(Hmi, TheMonitorsHistoryIsServedToThePage) {
  const std::string ads = std::string(VIRTCOM_SOURCE_DIR) + "/examples/ads-cell";
  const std::string db = (fs::temp_directory_path() / ("virtcom-hmi-monitor-" + std::to_string(::getpid()) + ".sqlite")).string();
  fs::remove(db);
  {
    ServerProcess plant(kExe, {"serve", ads + "/cell.yaml", "--ads", "127.0.0.1:0", "--quiet"}, ads, "ads: serving on ");
    ASSERT_GT(plant.port(), 0) << plant.errorOutput();
    ServerProcess monitor(kExe,
                          {"monitor", ads + "/cell.yaml", "--ads", "127.0.0.1:" + std::to_string(plant.port()), "--http", "127.0.0.1:0",
                           "--quiet", "--history", db},
                          ads, kAnnounce);
    ASSERT_GT(monitor.port(), 0) << monitor.errorOutput();
    const std::string check = "node -e \"const u = 'http://127.0.0.1:" + std::to_string(monitor.port()) +
                              "/api/'; (async () => { const m = await (await fetch(u + 'model')).json();"
                              " const r = await (await fetch(u + 'history/runs')).json();"
                              " process.exit(m.history && !m.replay && r.runs.length === 1 && !r.runs[0].ended ? 0 : 1); })()\"";
    std::string out;
    EXPECT_EQ(shell(check, out), 0) << out << monitor.errorOutput();
    EXPECT_EQ(monitor.stop(), 0) << monitor.errorOutput();
    EXPECT_EQ(plant.stop(), 0) << plant.errorOutput();
  }
  fs::remove(db);
}

// A write and a force POSTed to the HMI of `virtcom ARGS` (by node's fetch, no browser needed) are
// audited with the HTTP client's address, and counted in the end summary (docs/security.md).
// `exitStatus`: the command's, once stopped (SIGTERM).
void expectHttpWritesAudited(const std::vector<std::string>& args, int exitStatus) {
  ServerProcess cell(kExe, args, kGearbox, kAnnounce);
  ASSERT_GT(cell.port(), 0) << cell.errorOutput();
  const std::string post = "node -e \"const u = 'http://127.0.0.1:" + std::to_string(cell.port()) +
                           "/api/write'; const w = (b) => fetch(u, {method: 'POST', body: JSON.stringify(b)}).then((r) => r.status);"
                           " (async () => { const a = await w({name: 'MAIN.jobCount', value: '7'});"
                           " const b = await w({name: 'MAIN.failed', value: 'TRUE', force: true});"
                           " const c = await w({name: 'MAIN.nothing', value: '1'});"
                           " process.exit(a === 200 && b === 200 && c === 404 ? 0 : 1); })()\"";
  std::string out;
  ASSERT_EQ(shell(post, out), 0) << out;
  ASSERT_TRUE(cell.waitFor("(forced)")) << cell.errorOutput();
  EXPECT_EQ(cell.stop(), exitStatus) << cell.errorOutput();
  const std::string log = cell.errorOutput();
  EXPECT_NE(log.find(" http 127.0.0.1:"), std::string::npos) << log;
  EXPECT_NE(log.find(" MAIN.jobCount: "), std::string::npos) << log;
  EXPECT_NE(log.find(" -> 7\n"), std::string::npos) << log;
  EXPECT_NE(log.find(" MAIN.failed: FALSE -> TRUE (forced)\n"), std::string::npos) << log;
  EXPECT_NE(log.find("audit: 2 external writes (ads 0, modbus 0, opcua 0, http 2)"), std::string::npos) << log;
}

// The run's HTML report lists them: heading with the counts, a row per write.
void expectWritesListed(const std::string& reportFile) {
  const std::string html = virtcom::test::readFile(reportFile);
  EXPECT_NE(html.find("<h2>2 external writes (ads 0, modbus 0, opcua 0, http 2)<span"), std::string::npos) << html;
  for (const char* cells : {"</td><td class=\"l\">http</td><td class=\"l\">127.0.0.1:", "</td><td class=\"l\">MAIN.jobCount</td>",
                            " \u2192 7</td></tr>", "<td class=\"l\">MAIN.failed</td><td class=\"l wrap\">FALSE \u2192 TRUE (forced)</td></tr>"})
    EXPECT_NE(html.find(cells), std::string::npos) << cells << "\n" << html;
}

TEST(Hmi, WritesAndForcesThroughTheHttpApiAreAudited) {
  expectHttpWritesAudited({"serve", kGearbox + "/cell.yaml", "--http", "127.0.0.1:0", "--quiet", "--audit-writes", "each"}, 0);
}

// `run --hmi` audits the page's writes as `serve --http` does, and its HTML report lists them.
TEST(Hmi, RunWithTheHmiAuditsItsWritesToo) {
  const std::string report = (fs::temp_directory_path() / ("virtcom-hmi-writes-" + std::to_string(::getpid()) + ".html")).string();
  expectHttpWritesAudited(
      {"run", kGearbox + "/cell.yaml", "--hmi", "127.0.0.1:0", "--quiet", "--audit-writes", "each", "--report", report}, 3);  // 3: interrupted
  expectWritesListed(report);
  fs::remove(report);
}

TEST(Hmi, BindingBeyondLoopbackNeedsAnAllowList) {
  std::string out;
  EXPECT_EQ(shell(kExe + " serve '" + kGearbox + "/cell.yaml' --http 0.0.0.0:0 --quiet", out), 64) << out;
  EXPECT_NE(out.find("--http-allow"), std::string::npos) << out;
}

TEST(Hmi, ABadAddressIsAUsageError) {
  std::string out;
  EXPECT_EQ(shell(kExe + " run '" + kGearbox + "/cell.yaml' --hmi 127.0.0.1:http --quiet", out), 64) << out;
  EXPECT_NE(out.find("--hmi:"), std::string::npos) << out;
}

TEST(Hmi, HelpNamesTheOptions) {
  std::string out;
  EXPECT_EQ(shell(kExe + " serve --help", out), 0) << out;
  for (const char* option : {"--http", "--http-allow", "--allow-any-peer", "--hmi-token", "--hmi-readonly", "--hmi-paused"})
    EXPECT_NE(out.find(option), std::string::npos) << option;
  out.clear();
  EXPECT_EQ(shell(kExe + " run --help", out), 0) << out;
  EXPECT_NE(out.find("--hmi "), std::string::npos) << out;
}

}  // namespace
