// End-to-end: `virtcom run/serve --history` and `virtcom history` as a user runs them: exports
// byte-identical to the run's own files, time ranges, errors with their exit status, drops
// reported, and a `serve` killed with SIGKILL leaving a readable history.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "server_process.hpp"
#include "shell_command.hpp"
#include "support/eventually.hpp"
#include "support/read_file.hpp"

namespace {

namespace fs = std::filesystem;
using virtcom::e2e::ServerProcess;
using virtcom::e2e::shell;
using virtcom::test::readFile;
using ::testing::HasSubstr;

const std::string kExe = VIRTCOM_EXE;
const std::string kData = VIRTCOM_E2E_DATA;
const std::string kGearbox = std::string(VIRTCOM_SOURCE_DIR) + "/examples/gearbox-cell/cell.yaml";
constexpr int kHistoryError = 4;
constexpr int kUsage = 64;

class History : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    work_ = fs::path(::testing::TempDir()) / ("virtcom_history_e2e_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(work_);
    fs::create_directories(work_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(work_, ec);
  }
  std::string out(const std::string& name) const { return (work_ / name).string(); }
  // `virtcom ARGS` with stdout and stderr in `output`; the exit status.
  int virtcom(const std::string& args, std::string& output) {
    output.clear();
    return shell(kExe + " " + args, output);
  }
  // One integer from the history file, read with SQLite directly (as another program would).
  int64_t sqlInt(const std::string& db, const std::string& sql) {
    sqlite3* h = nullptr;
    int64_t value = -1;
    if (sqlite3_open_v2(db.c_str(), &h, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK) {
      sqlite3_stmt* s = nullptr;
      if (sqlite3_prepare_v2(h, sql.c_str(), -1, &s, nullptr) == SQLITE_OK && sqlite3_step(s) == SQLITE_ROW) value = sqlite3_column_int64(s, 0);
      sqlite3_finalize(s);
    }
    sqlite3_close(h);
    return value;
  }
  fs::path work_;
};

// The acceptance check of the historian: what `run` wrote and what `history` rebuilds from the
// database are the same bytes.
TEST_F(History, WholeRunExportIsByteIdenticalToTheRunsOwnFiles) {
  std::string output;
  const std::string db = out("h.sqlite");
  ASSERT_EQ(virtcom("run " + kGearbox + " --set MAIN.sequence=3 --quiet --csv " + out("run.csv") + " --vcd " + out("run.vcd") + " --json " +
                        out("run.json") + " --report " + out("run.html") + " --history " + db,
                    output),
            0)
      << output;
  EXPECT_THAT(output, HasSubstr("history: run 1 recorded in " + db));
  ASSERT_EQ(virtcom("history " + db + " --csv " + out("h.csv") + " --vcd " + out("h.vcd") + " --json " + out("h.json") + " --report " +
                        out("h.html"),
                    output),
            0)
      << output;
  for (const char* ext : {"csv", "vcd", "json", "html"}) {
    std::string ran = readFile(out(std::string("run.") + ext));
    EXPECT_GT(ran.size(), 500u) << ext;
    // The run's JSON also says how its clock went (run.time, docs/report.md), which the
    // historian does not record: everything else is the same.
    if (const size_t time = ran.find(",\n    \"time\": {"); time != std::string::npos && std::string(ext) == "json")
      ran.erase(time, ran.find('}', time) + 1 - time);
    EXPECT_TRUE(ran == readFile(out(std::string("h.") + ext))) << ext << " differs";
  }
}

TEST_F(History, ListsEveryRunWithHowItEnded) {
  std::string output;
  const std::string db = out("h.sqlite");
  ASSERT_EQ(virtcom("run " + kGearbox + " --set MAIN.sequence=3 --quiet --history " + db, output), 0) << output;
  ASSERT_EQ(virtcom("run " + kData + "/cells/pressing_forever.yaml --time-limit 5s --quiet --history " + db, output), 3) << output;
  ASSERT_EQ(virtcom("history " + db, output), 0) << output;
  EXPECT_THAT(output, HasSubstr("run  cell"));
  EXPECT_THAT(output, HasSubstr("changes  activities   drops  writes"));
  EXPECT_THAT(output, ::testing::ContainsRegex("\n1    gearbox-cell +[0-9-]+ [0-9:]+ +[0-9.]+  completed +[0-9]+ +[0-9]+ +0 +0\n"));
  EXPECT_THAT(output, ::testing::ContainsRegex("\n2    pressing-forever +[0-9-]+ [0-9:]+ +5.000  time limit reached +[0-9]+ +[0-9]+ +0 +0\n"));
  ASSERT_EQ(virtcom("history " + db + " --run 1", output), 0) << output;
  EXPECT_THAT(output, HasSubstr("gearbox-cell"));
  EXPECT_EQ(output.find("pressing-forever"), std::string::npos) << output;
}

// A range is a run of its own from 0: the values just before --from, then the changes inside.
TEST_F(History, TimeRangeExportStartsAtZeroWithTheValuesBeforeIt) {
  std::string output;
  const std::string db = out("h.sqlite");
  ASSERT_EQ(virtcom("run " + kData + "/cells/pressing_forever.yaml --time-limit 10s --quiet --history " + db, output), 3) << output;
  ASSERT_EQ(virtcom("history " + db + " --from 2s --to 3500ms --csv " + out("part.csv") + " --json " + out("part.json"), output), 0) << output;
  const std::string csv = readFile(out("part.csv"));
  ASSERT_EQ(csv.rfind("time_s,signal,value\n", 0), 0u) << csv;
  std::istringstream lines(csv);
  std::string line;
  std::getline(lines, line);
  double last = 0;
  int rows = 0;
  while (std::getline(lines, line)) {
    last = std::stod(line.substr(0, line.find(',')));
    EXPECT_LE(last, 1.5) << line;
    ++rows;
  }
  EXPECT_GT(rows, 10);
  EXPECT_GT(last, 0.0);
  EXPECT_THAT(readFile(out("part.json")), HasSubstr("\"duration_s\": 1.5"));
}

TEST_F(History, BadFilesAndRunsAreClearErrors) {
  std::string output;
  EXPECT_EQ(virtcom("history " + out("missing.sqlite"), output), kHistoryError);
  EXPECT_THAT(output, HasSubstr("error: " + out("missing.sqlite") + ": no such file"));

  std::ofstream(out("notes.txt")) << "not a database, just some notes that are long enough to be looked at\n";
  EXPECT_EQ(virtcom("history " + out("notes.txt"), output), kHistoryError);
  EXPECT_THAT(output, HasSubstr("notes.txt: not a SQLite database (file is not a database)"));

  {
    sqlite3* h = nullptr;
    ASSERT_EQ(sqlite3_open(out("other.sqlite").c_str(), &h), SQLITE_OK);
    ASSERT_EQ(sqlite3_exec(h, "CREATE TABLE orders (id INTEGER)", nullptr, nullptr, nullptr), SQLITE_OK);
    sqlite3_close(h);
  }
  EXPECT_EQ(virtcom("history " + out("other.sqlite"), output), kHistoryError);
  EXPECT_THAT(output, HasSubstr("other.sqlite: a SQLite database of another application, not a virtcom history"));
  // ... and recording into it is refused before the run.
  EXPECT_EQ(virtcom("run " + kGearbox + " --quiet --history " + out("other.sqlite"), output), kHistoryError);
  EXPECT_THAT(output, HasSubstr("error: --history: " + out("other.sqlite") + ": a SQLite database of another application"));
  EXPECT_EQ(virtcom("run " + kGearbox + " --quiet --history " + work_.string(), output), kHistoryError);
  EXPECT_THAT(output, HasSubstr("error: --history: " + work_.string() + ": cannot open"));

  const std::string db = out("h.sqlite");
  ASSERT_EQ(virtcom("run " + kGearbox + " --set MAIN.sequence=3 --quiet --history " + db, output), 0) << output;
  EXPECT_EQ(virtcom("history " + db + " --run 5 --csv " + out("x.csv"), output), kHistoryError);
  EXPECT_THAT(output, HasSubstr("error: " + db + ": no run 5 (virtcom history " + db + " lists the runs)"));
  EXPECT_EQ(virtcom("history " + db + " --from soon --csv " + out("x.csv"), output), kUsage);
  EXPECT_THAT(output, HasSubstr("error: --from: 'soon' is not a duration (e.g. 10s, 1500ms, T#1m30s)"));
  EXPECT_EQ(virtcom("history " + db + " --from 5s --to 1s --csv " + out("x.csv"), output), kUsage);
  EXPECT_THAT(output, HasSubstr("error: --from 5s is after --to 1s"));
  EXPECT_EQ(virtcom("history " + db + " --from 5s", output), kUsage);
  EXPECT_THAT(output, HasSubstr("error: --from, --to and --signal select what is exported: add --csv, --vcd, --report or --json"));
}

// `virtcom history FILE --http` (browsed in tests/e2e/hmi_e2e_test.cpp): its options' mistakes.
TEST_F(History, BrowsingOptionsAreChecked) {
  std::string output;
  const std::string db = out("h.sqlite");
  EXPECT_EQ(virtcom("history " + db + " --http 127.0.0.1:0 --csv " + out("x.csv"), output), kUsage);
  EXPECT_THAT(output, HasSubstr("error: --http browses the history in the web HMI: it takes no --csv"));
  EXPECT_EQ(virtcom("history " + db + " --http 127.0.0.1:0 --from 1s", output), kUsage);
  EXPECT_THAT(output, HasSubstr("error: --http browses the history in the web HMI"));
  EXPECT_EQ(virtcom("history " + db + " --cell " + kGearbox, output), kUsage);
  EXPECT_THAT(output, HasSubstr("error: --cell, --http-allow and --allow-any-peer go with --http"));
  ASSERT_EQ(virtcom("run " + kGearbox + " --set MAIN.sequence=3 --quiet --history " + db, output), 0) << output;
  EXPECT_EQ(virtcom("history " + db + " --http 0.0.0.0:0", output), kUsage);
  EXPECT_THAT(output, HasSubstr("error: --http: 0.0.0.0 is reachable beyond this machine"));
  EXPECT_EQ(virtcom("history " + db + " --http 127.0.0.1:0 --run 7", output), kHistoryError);
  EXPECT_THAT(output, HasSubstr("no run 7: the page draws the layout of a run's cell file (or give --cell CELL.yaml)"));
  EXPECT_EQ(virtcom("history " + db + " --http 127.0.0.1:0 --cell " + out("none.yaml"), output), kUsage);
  EXPECT_THAT(output, HasSubstr("error: --http: the page draws the layout of " + out("none.yaml") + ", which does not load"));
}

TEST_F(History, HelpNamesEveryOption) {
  std::string output;
  ASSERT_EQ(virtcom("--help", output), 0);
  EXPECT_THAT(output, HasSubstr("history"));
  ASSERT_EQ(virtcom("history --help", output), 0);
  for (const char* option : {"--run", "--from", "--to", "--csv", "--vcd", "--report", "--json", "--signal", "--http", "--http-allow",
                             "--allow-any-peer", "--cell"})
    EXPECT_THAT(output, HasSubstr(option)) << option;
  for (const char* command : {"run", "serve"}) {
    ASSERT_EQ(virtcom(std::string(command) + " --help", output), 0);
    for (const char* option : {"--history ", "--history-keep-days", "--history-max-mb", "--history-queue"})
      EXPECT_THAT(output, HasSubstr(option)) << command << " " << option;
  }
}

// Paced to the wall clock (here 2000 times real time), a queue of one event cannot keep up: events
// are dropped, counted, and reported on stderr and in the listing; the run is not held up.
TEST_F(History, FullQueueDropsAreCountedAndReported) {
  std::string output;
  const std::string db = out("h.sqlite");
  ASSERT_EQ(virtcom("run " + kData + "/cells/pressing_forever.yaml --time-limit 600s --speed 2000 --quiet --history-queue 1 --history " + db,
                    output),
            3)
      << output;
  EXPECT_THAT(output, ::testing::ContainsRegex("warning: history: [1-9][0-9]* event\\(s\\) dropped"));
  const int64_t drops = sqlInt(db, "SELECT drops FROM runs WHERE id = 1");
  EXPECT_GT(drops, 0);
  ASSERT_EQ(virtcom("history " + db, output), 0) << output;
  EXPECT_THAT(output, HasSubstr(" " + std::to_string(drops) + "       0\n"));
}

// In virtual time nothing is late: the same tiny queue makes the simulation wait, nothing is lost.
TEST_F(History, RunInVirtualTimeWaitsInsteadOfDropping) {
  std::string output;
  const std::string db = out("h.sqlite");
  ASSERT_EQ(virtcom("run " + kData + "/cells/pressing_forever.yaml --time-limit 60s --quiet --history-queue 1 --csv " + out("run.csv") +
                        " --history " + db,
                    output),
            3)
      << output;
  EXPECT_EQ(output.find("dropped"), std::string::npos) << output;
  EXPECT_EQ(sqlInt(db, "SELECT drops FROM runs WHERE id = 1"), 0);
  ASSERT_EQ(virtcom("history " + db + " --csv " + out("h.csv"), output), 0) << output;
  EXPECT_TRUE(readFile(out("run.csv")) == readFile(out("h.csv")));
}

// Durability: SIGKILL (no chance to clean up) while serving; what was committed before stays
// readable, the file passes the integrity check, the run is listed as not ended.
TEST_F(History, ServeKilledWithSigkillLeavesAReadableHistory) {
  const std::string db = out("h.sqlite");
  ServerProcess serve(kExe, {"serve", kData + "/cells/pressing_forever.yaml", "--ads", "127.0.0.1:0", "--quiet", "--history", db}, kData,
                      "ads: serving on ");
  ASSERT_GT(serve.port(), 0) << serve.errorOutput();
  // Until 1.5 s of virtual (here: wall) time are committed, then ~0.5 s more.
  ASSERT_TRUE(virtcom::test::eventually([&] { return sqlInt(db, "SELECT end_ns FROM runs WHERE id = 1") >= 1'500'000'000; }))
      << serve.errorOutput();
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_EQ(serve.signal(SIGKILL), 128 + SIGKILL);
  const int64_t recordedNs = sqlInt(db, "SELECT end_ns FROM runs WHERE id = 1");
  EXPECT_GE(recordedNs, 1'500'000'000);
  // Changes up to within a second of what was recorded (the press toggles every 0.2-0.3 s).
  EXPECT_GE(sqlInt(db, "SELECT MAX(t_ns) FROM changes WHERE run = 1"), recordedNs - 1'000'000'000);
  EXPECT_GT(sqlInt(db, "SELECT COUNT(*) FROM activities WHERE run = 1"), 0);
  std::string output;
  ASSERT_EQ(virtcom("history " + db, output), 0) << output;  // quick_check passed
  EXPECT_THAT(output, HasSubstr("pressing-forever"));
  EXPECT_THAT(output, HasSubstr("not ended: running or killed"));
  ASSERT_EQ(virtcom("history " + db + " --json " + out("killed.json"), output), 0) << output;
  EXPECT_THAT(readFile(out("killed.json")), HasSubstr("the recording stopped before the run ended"));
}

// The audited writes of a served run (docs/security.md) go into its history, one row each, and
// its JSON report counts them per protocol, beside the run's late ticks (a served run is paced).
TEST_F(History, ServedWritesAreRecordedAndCountedInTheReport) {
  const std::string db = out("h.sqlite"), json = out("served.json");
  const std::string gearboxDir = fs::path(kGearbox).parent_path().string();
  ServerProcess serve(kExe, {"serve", kGearbox, "--http", "127.0.0.1:0", "--quiet", "--history", db, "--json", json}, gearboxDir,
                      "hmi: serving http://");
  ASSERT_GT(serve.port(), 0) << serve.errorOutput();
  std::string output;
  ASSERT_EQ(shell("node -e \"fetch('http://127.0.0.1:" + std::to_string(serve.port()) +
                      "/api/write', {method: 'POST', body: JSON.stringify({name: 'MAIN.jobCount', value: '9'})})"
                      ".then((r) => process.exit(r.status === 200 ? 0 : 1))\"",
                  output),
            0)
      << output;
  // Committed by the historian's writer within its flush period (200 ms).
  ASSERT_TRUE(virtcom::test::eventually([&] { return sqlInt(db, "SELECT COUNT(*) FROM writes WHERE run = 1") == 1; }))
      << serve.errorOutput();
  EXPECT_EQ(serve.stop(), 0) << serve.errorOutput();
  EXPECT_EQ(sqlInt(db, "SELECT COUNT(*) FROM writes WHERE run = 1 AND protocol = 'http' AND peer LIKE '127.0.0.1:%' "
                       "AND variable = 'MAIN.jobCount' AND new_value = '9' AND forced = 0"),
            1);
  EXPECT_THAT(serve.errorOutput(), HasSubstr("audit: 1 external writes (ads 0, modbus 0, opcua 0, http 1)"));
  const std::string report = readFile(json);
  EXPECT_THAT(report, HasSubstr("\"external_writes\": {\n      \"total\": 1,"));
  EXPECT_THAT(report, HasSubstr("\"http\": 1"));
  EXPECT_THAT(report, HasSubstr("\"late_ticks\": "));
  // `virtcom history` counts them in its table and lists them as the audit logged them.
  ASSERT_EQ(virtcom("history " + db, output), 0) << output;
  EXPECT_THAT(output, HasSubstr("  writes\n"));
  EXPECT_THAT(output, testing::MatchesRegex("(.|\n)*   1\n$"));
  ASSERT_EQ(virtcom("history " + db + " --run 1 --writes", output), 0) << output;
  EXPECT_THAT(output, testing::MatchesRegex("[0-9]+\\.[0-9]{3}s 20[0-9-]+T[0-9:.]+Z http 127\\.0\\.0\\.1:[0-9]+ MAIN\\.jobCount: [0-9]+ -> 9\n"));
  ASSERT_EQ(virtcom("history " + db + " --writes --from 1000s", output), 0) << output;
  EXPECT_EQ(output, "") << "no write after 1000 s";
  // Its reports exported from the history count them as the served run's did, and the HTML
  // report lists the write.
  ASSERT_EQ(virtcom("history " + db + " --json " + out("history.json") + " --report " + out("history.html"), output), 0) << output;
  EXPECT_THAT(readFile(out("history.json")), HasSubstr("\"external_writes\": {\n      \"total\": 1,"));
  const std::string html = readFile(out("history.html"));
  EXPECT_THAT(html, HasSubstr("<h2>1 external writes (ads 0, modbus 0, opcua 0, http 1)<span"));
  EXPECT_THAT(html, testing::ContainsRegex("<td class=\"l\">http</td><td class=\"l\">127\\.0\\.0\\.1:[0-9]+</td>"
                                           "<td class=\"l\">MAIN\\.jobCount</td><td class=\"l wrap\">[0-9]+ \u2192 9</td></tr>"));
}

}  // namespace
