// End-to-end tests of `virtcom run`: the built binary (VIRTCOM_EXE) simulates the gearbox
// example (examples/gearbox-cell) or a cell in tests/e2e/data/cells and is checked on its exit
// code, output and report files, as a user sees them. The child runs in tests/e2e/data, so
// diagnostics show short relative names; report files go to a per-test temporary folder.
//
// The HTML report test also screenshots the page in headless Chromium when /usr/bin/chromium
// exists (skipped otherwise; with VIRTCOM_REQUIRE_BROWSER=1, as `make test` sets, a missing
// browser fails the test instead).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "csv_trace.hpp"
#include "support/read_file.hpp"

namespace fs = std::filesystem;

namespace {

using virtcom::test::readFile;

const char* const kExe = VIRTCOM_EXE;
const char* const kDataDir = VIRTCOM_E2E_DATA;
const std::string kGearbox = std::string(VIRTCOM_SOURCE_DIR) + "/examples/gearbox-cell/cell.yaml";
const std::string kGearboxSfc = std::string(VIRTCOM_SOURCE_DIR) + "/examples/gearbox-cell/cell-sfc.yaml";
const std::string kGearboxDrives = std::string(VIRTCOM_SOURCE_DIR) + "/examples/gearbox-cell/cell-drives.yaml";
const std::string kGoldenDir = std::string(VIRTCOM_SOURCE_DIR) + "/tests/golden/cells";
const char* const kChromium = "/usr/bin/chromium";

struct RunResult {
  int exitCode = -1;  // the process's exit status; 128 + signal if it was killed
  std::string out;
  std::string err;
  long maxRssKb = 0;  // the child's peak resident memory
};

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Whether the BOOL signals `a` and `b` of a `--csv` trace (time_s,signal,value rows of the
// changes, in time order) are 1 together after all the changes of some instant.
bool bothActiveAtSomeTime(const std::string& csv, const std::string& a, const std::string& b) {
  std::istringstream in(csv);
  std::string line, time;
  bool aOn = false, bOn = false;
  while (std::getline(in, line)) {
    size_t first = line.find(','), last = line.rfind(',');
    if (first == std::string::npos || first == last) continue;
    if (line.substr(0, first) != time && aOn && bOn) return true;
    time = line.substr(0, first);
    const std::string signal = line.substr(first + 1, last - first - 1);
    if (signal == a) aOn = line.substr(last + 1) == "1";
    if (signal == b) bOn = line.substr(last + 1) == "1";
  }
  return aOn && bOn;
}

std::string show(const RunResult& r) {
  return "exit " + std::to_string(r.exitCode) + "\n--- stdout ---\n" + r.out + "--- stderr ---\n" + r.err;
}

class RunCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    work_ = fs::path(::testing::TempDir()) / ("virtcom_run_e2e_" + std::string(info->test_suite_name()) + "_" +
                                              info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(work_);
    fs::create_directories(work_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(work_, ec);
  }

  // Runs `program args...` in the data folder and waits for it.
  RunResult exec(const std::string& program, const std::vector<std::string>& args) {
    const std::string outPath = (work_ / "stdout.txt").string();
    const std::string errPath = (work_ / "stderr.txt").string();
    std::vector<std::string> all{program};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = ::fork();
    if (pid < 0) {
      ADD_FAILURE() << "fork failed";
      return {};
    }
    if (pid == 0) {  // child: only async-signal-safe calls from here on
      int in = ::open("/dev/null", O_RDONLY);
      int out = ::open(outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      int err = ::open(errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (in < 0 || out < 0 || err < 0 || ::chdir(kDataDir) != 0) ::_exit(125);
      ::dup2(in, 0);
      ::dup2(out, 1);
      ::dup2(err, 2);
      ::execv(program.c_str(), argv.data());
      ::_exit(127);
    }
    int status = 0;
    struct rusage usage {};
    while (::wait4(pid, &status, 0, &usage) < 0) {
    }
    RunResult r;
    r.maxRssKb = usage.ru_maxrss;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = readFile(outPath);
    r.err = readFile(errPath);
    return r;
  }
  RunResult run(const std::vector<std::string>& args) { return exec(kExe, args); }
  std::string out(const std::string& name) const { return (work_ / name).string(); }

  fs::path work_;
};

class RunHelp : public RunCommand {};

TEST_F(RunHelp, ListsEveryOption) {
  RunResult r = run({"run", "--help"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_TRUE(contains(r.out, "Simulate a cell file")) << show(r);
  for (const char* option : {"cell", "--report", "--json", "--vcd", "--csv", "--until", "--time-limit", "--set",
                             "--signal", "--speed", "--backend", "--quiet"})
    EXPECT_TRUE(contains(r.out, option)) << option << "\n" << show(r);
  EXPECT_EQ(r.err, "");
}

// Regression test (found by the cell/sim test suite).
TEST_F(RunHelp, SetIsDescribedAsBeforeTheFirstScan) {
  RunResult r = run({"run", "--help"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_FALSE(contains(r.out, "after its first scan")) << show(r);
  EXPECT_TRUE(contains(r.out, "before its first scan")) << show(r);
}

TEST_F(RunHelp, TopLevelHelpListsRun) {
  RunResult r = run({"--help"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_TRUE(contains(r.out, "run")) << show(r);
}

class RunExit : public RunCommand {};

// Sequence 3 completes: exit 0, the summary on stdout, and the JSON report is the golden one
// (tests/golden/cells, checked against the library in tests/unit/sim/gearbox_golden_test.cpp).
TEST_F(RunExit, Sequence3CompletesAndWritesEveryReport) {
  RunResult r = run({"run", kGearbox, "--set", "MAIN.sequence=3", "--json", out("seq3.json"), "--vcd", out("seq3.vcd"),
                     "--csv", out("seq3.csv")});
  ASSERT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.err, "");
  EXPECT_TRUE(contains(r.out, "Run ended     completed: 1 cycle(s) completed")) << show(r);
  EXPECT_TRUE(contains(r.out, "Collisions    0")) << show(r);
  for (const char* device : {"Robot1", "Robot2", "Press", "AxisX", "AxisY"})
    EXPECT_TRUE(contains(r.out, device)) << device << "\n" << show(r);
  EXPECT_EQ(readFile(out("seq3.json")), readFile(kGoldenDir + "/gearbox-seq3.json"));

  // VCD (IEEE 1364 §18): header sections first, 1 ns timescale, then the definitions. The
  // writer leaves out the optional $date on purpose (report/waveform.hpp: deterministic output).
  const std::string vcd = readFile(out("seq3.vcd"));
  EXPECT_EQ(vcd.rfind("$version virtcom $end\n$timescale 1 ns $end\n", 0), 0u) << vcd.substr(0, 200);
  EXPECT_FALSE(contains(vcd, "$date"));
  EXPECT_TRUE(contains(vcd, "$scope module Robot1 $end")) << vcd.substr(0, 400);
  EXPECT_TRUE(contains(vcd, "$enddefinitions $end\n"));
  EXPECT_TRUE(contains(vcd, "#0\n$dumpvars\n"));

  // CSV: header, then every signal's initial value at time 0
  const std::string csv = readFile(out("seq3.csv"));
  EXPECT_EQ(csv.rfind("time_s,signal,value\n0.000000000,Robot1.procedureNumber,0\n0.000000000,Robot1.execute,0\n", 0),
            0u)
      << csv.substr(0, 200);
  EXPECT_TRUE(contains(csv, ",MAIN.jobsFinished,")) << "run.record adds MAIN.jobsFinished";
}

// --backend aot runs the cell's PLC as machine code: the same golden report and VCD as the
// interpreter. The compiled module is cached in the test's own folder.
TEST_F(RunExit, AotBackendWritesTheSameReport) {
  ::setenv("VIRTCOM_AOT_CACHE", out("aot").c_str(), 1);
  RunResult r = run({"run", kGearbox, "--set", "MAIN.sequence=3", "--json", out("aot.json"), "--vcd", out("aot.vcd"),
                     "--backend", "aot"});
  RunResult interp = run({"run", kGearbox, "--set", "MAIN.sequence=3", "--vcd", out("interp.vcd")});
  ::unsetenv("VIRTCOM_AOT_CACHE");
  ASSERT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.err, "") << "no fallback notice";
  EXPECT_TRUE(fs::exists(out("aot"))) << "nothing compiled";
  EXPECT_EQ(readFile(out("aot.json")), readFile(kGoldenDir + "/gearbox-seq3.json"));
  EXPECT_EQ(readFile(out("aot.vcd")), readFile(out("interp.vcd")));
}

// --backend auto (the default) switches to machine code between two scans: forced after scan 100
// and after scan 1000 (the test hook), in event-driven and in tick-stepped time, the JSON report
// and the VCD are the interpreter's, byte for byte. The log line shows the switch happened.
TEST_F(RunExit, AutoBackendSwitchingMidRunWritesTheSameReport) {
  ::setenv("VIRTCOM_AOT_CACHE", out("aot").c_str(), 1);
  ::setenv("VIRTCOM_TIER_LOG", "1", 1);
  for (const std::string mode : {"event", "tick"}) {
    RunResult interp = run({"run", kGearbox, "--set", "MAIN.sequence=3", "--time-mode", mode, "--json",
                            out(mode + "-interp.json"), "--vcd", out(mode + "-interp.vcd"), "--backend", "interp"});
    ASSERT_EQ(interp.exitCode, 0) << show(interp);
    for (const std::string at : {"100", "1000"}) {
      SCOPED_TRACE(mode + " time, switch after scan " + at);
      ::setenv("VIRTCOM_TIER_SWITCH_AT_SCAN", at.c_str(), 1);
      const std::string name = mode + "-" + at;
      RunResult r = run({"run", kGearbox, "--set", "MAIN.sequence=3", "--time-mode", mode, "--json",
                         out(name + ".json"), "--vcd", out(name + ".vcd")});
      ::unsetenv("VIRTCOM_TIER_SWITCH_AT_SCAN");
      ASSERT_EQ(r.exitCode, 0) << show(r);
      EXPECT_TRUE(contains(r.err, "tier: --backend auto: " + at + " scans interpreted, ")) << show(r);
      EXPECT_TRUE(contains(r.err, ", switched at ")) << show(r);
      EXPECT_EQ(readFile(out(name + ".json")), readFile(out(mode + "-interp.json")));
      EXPECT_EQ(readFile(out(name + ".vcd")), readFile(out(mode + "-interp.vcd")));
    }
  }
  ::unsetenv("VIRTCOM_TIER_LOG");
  ::unsetenv("VIRTCOM_AOT_CACHE");
}

// Also shows that --set is applied before the first scan: the program loads its job list in
// the first scan, and the run is sequence 4's (the golden file), not the default sequence 3.
TEST_F(RunExit, CollisionIsExit3) {
  RunResult r = run({"run", kGearbox, "--set", "MAIN.sequence=4", "--json", out("seq4.json")});
  EXPECT_EQ(r.exitCode, 3) << show(r);
  EXPECT_TRUE(contains(r.out, "Run ended     collision: robots collided in a shared zone")) << show(r);
  EXPECT_TRUE(contains(r.out, "zone SharedTable: Robot1 (PlaceBearing) <-> Robot2 (ScrewStud)")) << show(r);
  EXPECT_EQ(readFile(out("seq4.json")), readFile(kGoldenDir + "/gearbox-seq4.json"));
}

TEST_F(RunExit, TimeLimitIsExit3) {
  RunResult r = run({"run", kGearbox, "--set", "MAIN.sequence=3", "--time-limit", "5s", "--json", out("limit.json")});
  EXPECT_EQ(r.exitCode, 3) << show(r);
  EXPECT_TRUE(contains(r.out, "Run ended     time limit reached")) << show(r);
  EXPECT_TRUE(contains(r.out, "Run time      5.000 s")) << show(r);
  const std::string json = readFile(out("limit.json"));
  EXPECT_TRUE(contains(json, "\"end\": \"time_limit\"")) << json.substr(0, 400);
  EXPECT_TRUE(contains(json, "\"duration_s\": 5.0,")) << json.substr(0, 400);
}

TEST_F(RunExit, BrokenCellFileIsExit1WithEveryMistake) {
  RunResult r = run({"run", "cells/broken.yaml", "--json", out("never.json")});
  EXPECT_EQ(r.exitCode, 1) << show(r);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err,
            "cells/broken.yaml:11:5: error[C011]: unknown key 'busy_powr' in device (expected one of: name, type, "
            "wiring, faults, model, description, command_port, idle_power, busy_power, commands, group)\n"
            "      busy_powr: 100 W\n"
            "      ^\n"
            "cells/broken.yaml:13:35: error[C010]: 'duration': '1' needs a unit: expected a duration (e.g. 2 s, 150 ms)\n"
            "        1: { name: Close, duration: 1 }\n"
            "                                    ^\n"
            "2 error(s), 0 warning(s)\n");
  EXPECT_FALSE(fs::exists(out("never.json")));
}

TEST_F(RunExit, MissingCellFileIsAUsageError) {
  RunResult r = run({"run", "cells/nowhere.yaml"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_TRUE(contains(r.err, "cells/nowhere.yaml")) << show(r);
}

TEST_F(RunExit, BadUntilAndSetAreUsageErrors) {
  RunResult r = run({"run", kGearbox, "--until", "MAIN.nothing >= 5"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_TRUE(contains(r.err, "error[C020]: condition 'MAIN.nothing >= 5': the PLC has no variable 'MAIN.nothing'"))
      << show(r);
  EXPECT_EQ(r.out, "");
  r = run({"run", kGearbox, "--set", "MAIN.sequense=3"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_TRUE(contains(r.err, "error: --set unknown variable 'MAIN.sequense'")) << show(r);
  r = run({"run", kGearbox, "--time-limit", "soon"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_TRUE(contains(r.err, "--time-limit: 'soon' is not a duration")) << show(r);
}

TEST_F(RunExit, UntilStopsEarly) {
  RunResult r = run({"run", kGearbox, "--set", "MAIN.sequence=3", "--until", "MAIN.jobsFinished >= 5", "--csv",
                     out("until.csv")});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_TRUE(contains(r.out, "Run ended     completed: 'MAIN.jobsFinished >= 5' became true")) << show(r);
  EXPECT_TRUE(contains(r.out, "Run time      7.640 s")) << show(r);  // of 70.95 s for the whole cycle
  // the last recorded value of MAIN.jobsFinished is 5: the run stopped at the scan that made it 5
  const std::string csv = readFile(out("until.csv"));
  size_t last = csv.rfind(",MAIN.jobsFinished,");
  ASSERT_NE(last, std::string::npos);
  EXPECT_EQ(csv.substr(last, csv.find('\n', last) - last), ",MAIN.jobsFinished,5");
  // and it is the last change of the run
  EXPECT_EQ(csv.find('\n', last), csv.size() - 1) << csv.substr(last > 300 ? last - 300 : 0);
}

// A cell whose PLC program is a ladder diagram in PLCopen XML, mixed with an ST function block
// (cells/ld_handshake.yaml): loaded, compiled and run like ST sources.
TEST_F(RunExit, CellWithAPlcopenLadderProgramRuns) {
  RunResult r = run({"run", "cells/ld_handshake.yaml", "--csv", out("ld.csv")});
  ASSERT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.err, "");
  EXPECT_TRUE(contains(r.out, "Run ended     completed: 1 cycle(s) completed")) << show(r);
  // the rung `NOT finished -> exec` started the clamp once; the ST block counted that one start
  const std::string csv = readFile(out("ld.csv"));
  EXPECT_TRUE(contains(csv, ",MAIN.starts.count,1\n")) << csv;
  EXPECT_FALSE(contains(csv, ",MAIN.starts.count,2")) << csv;
  EXPECT_TRUE(contains(csv, ",Clamp.done,1\n")) << csv;
}

// --quiet leaves out the table, never why the run ended: the faults and the end reason go to
// stderr, stdout stays empty (issue 16: a division by zero used to exit 2 without a word).
TEST_F(RunExit, QuietStillSaysHowTheRunEnded) {
  RunResult r = run({"run", kGearbox, "--set", "MAIN.sequence=4", "--quiet"});
  EXPECT_EQ(r.exitCode, 3) << show(r);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "Faults        0\nRun ended     collision: robots collided in a shared zone\n") << show(r);
  r = run({"run", "cells/divzero.yaml", "--quiet"});
  EXPECT_EQ(r.exitCode, 2) << show(r);
  EXPECT_EQ(r.out, "");
  EXPECT_TRUE(contains(r.err, "Faults        1\n")) << show(r);
  EXPECT_TRUE(contains(r.err, "division by zero")) << show(r);
  EXPECT_TRUE(contains(r.err, "Run ended     PLC fault")) << show(r);
}

// PNG (ISO/IEC 15948 §5.2, §11.2.2): 8-byte signature, then the IHDR chunk: 4-byte big-endian
// length (13), "IHDR", width and height as 4-byte big-endian integers.
struct PngSize {
  bool ok = false;
  uint32_t width = 0, height = 0;
};

PngSize pngSize(const std::string& bytes) {
  static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  PngSize s;
  if (bytes.size() < 24) return s;
  for (size_t i = 0; i < 8; ++i)
    if (static_cast<unsigned char>(bytes[i]) != kSignature[i]) return s;
  if (bytes.compare(12, 4, "IHDR") != 0) return s;
  auto be32 = [&](size_t at) {
    uint32_t v = 0;
    for (size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
    return v;
  };
  if (be32(8) != 13) return s;
  s.width = be32(16);
  s.height = be32(20);
  s.ok = true;
  return s;
}

// The SFC version of the gearbox program (cell-sfc.yaml, plc/main_sfc.st) against the ST one
// (cell.yaml): the JSON report holds the measured cycle time and every device operation with
// its start and end, so equal reports mean the same cycle time and the same Gantt chart.
class RunSfc : public RunCommand {};

TEST_F(RunSfc, SameCycleTimeAndGanttAsTheStProgramForEverySequence) {
  for (const std::string sequence : {"1", "2", "3", "4"}) {
    const std::string set = "MAIN.sequence=" + sequence;
    // Stepped tick by tick: event-driven time skips the ST program's repeated scans but not the
    // chart's (its step times change every scan), and the JSON says how many (run.time).
    RunResult st = run({"run", kGearbox, "--quiet", "--time-mode", "tick", "--set", set, "--json", out("st" + sequence + ".json")});
    RunResult sfc = run({"run", kGearboxSfc, "--quiet", "--time-mode", "tick", "--set", set, "--json", out("sfc" + sequence + ".json")});
    EXPECT_EQ(sfc.exitCode, st.exitCode) << "sequence " << sequence << "\n" << show(sfc);
    EXPECT_EQ(sfc.err, st.err) << show(sfc);  // no diagnostics; --quiet's outcome lines alike
    const std::string json = readFile(out("sfc" + sequence + ".json"));
    EXPECT_TRUE(contains(json, "\"activities\": [\n    {")) << "sequence " << sequence << " ran no operation";
    EXPECT_EQ(json, readFile(out("st" + sequence + ".json"))) << "sequence " << sequence;
  }
}

// The chart's steps are PLC variables (MAIN.<Step>.X): cell-sfc.yaml records them, so the CSV
// shows when each device's branch runs a job, and `--signal` puts them on the report's timeline.
TEST_F(RunSfc, RecordsTheActiveStepsOfEveryBranch) {
  const std::vector<std::string> flags{"MAIN.Robot1Work.X", "MAIN.Robot2Work.X", "MAIN.PressWork.X",
                                       "MAIN.AxisXWork.X", "MAIN.AxisYWork.X"};
  std::vector<std::string> args{"run", kGearboxSfc, "--set", "MAIN.sequence=3", "--csv", out("seq3.csv"),
                                "--report", out("seq3.html")};
  for (const std::string& flag : flags) args.insert(args.end(), {"--signal", flag});
  RunResult r = run(args);
  ASSERT_EQ(r.exitCode, 0) << show(r);
  EXPECT_TRUE(contains(r.out, "Run ended     completed: 1 cycle(s) completed")) << show(r);
  const std::string csv = readFile(out("seq3.csv"));
  const std::string html = readFile(out("seq3.html"));
  for (const std::string& flag : flags) {
    EXPECT_TRUE(contains(csv, "," + flag + ",1\n")) << flag << " never became active";
    EXPECT_TRUE(contains(html, flag)) << flag << " is not in the report";
  }
  // Robot2 screws the first studs while Robot1 fetches the bearings: both branches work at once.
  EXPECT_TRUE(bothActiveAtSomeTime(csv, "MAIN.Robot1Work.X", "MAIN.Robot2Work.X"));
}

// The gearbox cell with its X/Y table on S120 EPos drives (cell-drives.yaml: the same PLC
// program plus plc/table_drives.st, robots and press taken from cell.yaml) against the ideal
// axes of cell.yaml.
class RunDrives : public RunCommand {
 protected:
  // The measured cycle time (s) of a JSON report, NAN if it has none.
  static double cycleTimeS(const std::string& json) {
    const size_t cycle = json.find("\"cycle\": {");
    const size_t time = json.find("\"time_s\": ", cycle);
    return cycle == std::string::npos || time == std::string::npos ? NAN : std::stod(json.substr(time + 10));
  }
};

// The drives follow the ideal axes' trapezoid (250 mm/s, 500 mm/s^2); on top come only the
// position loop's lag settling into the 40 LU positioning window (about 40 ms) and at most one
// more scan (10 ms) per handshake edge through TABLE: about 50 ms per move, and at most eight
// moves lie on the critical path, so the cycle is at most 1 % (0.71 s of sequence 3's 70.95 s)
// longer, and never shorter. Every move ends at its target: X at 420 mm and Y at 180 mm
// under the press, both back at 0 mm at the end, without passing a target.
TEST_F(RunDrives, CycleTimeWithinOnePercentOfTheIdealAxesAndTargetsReached) {
  for (const std::string sequence : {"1", "2", "3"}) {
    SCOPED_TRACE("sequence " + sequence);
    const std::string set = "MAIN.sequence=" + sequence;
    RunResult ideal = run({"run", kGearbox, "--quiet", "--set", set, "--json", out("ideal.json")});
    RunResult drives = run({"run", kGearboxDrives, "--set", set, "--json", out("drives.json"), "--csv", out("drives.csv")});
    ASSERT_EQ(ideal.exitCode, 0) << show(ideal);
    ASSERT_EQ(drives.exitCode, 0) << show(drives);
    EXPECT_EQ(drives.err, "");
    EXPECT_TRUE(contains(drives.out, "Run ended     completed: 1 cycle(s) completed")) << show(drives);
    const double idealS = cycleTimeS(readFile(out("ideal.json"))), drivesS = cycleTimeS(readFile(out("drives.json")));
    EXPECT_GE(drivesS, idealS);
    EXPECT_LE(drivesS, 1.01 * idealS);
    ::testing::Test::RecordProperty("cycle_time_ms_drives_sequence" + sequence, std::to_string(std::lround(drivesS * 1000)));

    const std::string csv = readFile(out("drives.csv"));
    struct Axis {
      const char* name;
      double pressMm;  // plc/jobs.st TableX/TableY(POS_PRESS)
    };
    for (const Axis& axis : {Axis{"AxisX", 420.0}, Axis{"AxisY", 180.0}}) {
      SCOPED_TRACE(axis.name);
      const std::vector<double> mm = values(csv, std::string(axis.name) + ".position");  // the lead screw's load
      ASSERT_FALSE(mm.empty());
      constexpr double kWindowMm = 0.04;  // p2544 = 40 LU
      EXPECT_NEAR(*std::max_element(mm.begin(), mm.end()), axis.pressMm, kWindowMm);
      EXPECT_GE(*std::min_element(mm.begin(), mm.end()), -kWindowMm);
      EXPECT_NEAR(mm.back(), 0.0, kWindowMm);
      // the PLC's view through the telegram (XIST_A in LU, scaled by table_drives.st)
      const std::vector<double> plc = values(csv, "MAIN." + std::string(axis.name) + ".actualPosition");
      ASSERT_FALSE(plc.empty());
      EXPECT_NEAR(*std::max_element(plc.begin(), plc.end()), axis.pressMm, kWindowMm);
    }
    if (sequence == "3") {
      EXPECT_EQ(readFile(out("drives.json")), readFile(kGoldenDir + "/gearbox-drives-seq3.json"));
    }
  }
}

// Sequence 4 lets both robots into the shared table zone together: the drive variant detects
// the same collision as the ideal cell.
TEST_F(RunDrives, Sequence4StillCollides) {
  const std::string collision = "zone SharedTable: Robot1 (PlaceBearing) <-> Robot2 (ScrewStud)";
  RunResult ideal = run({"run", kGearbox, "--set", "MAIN.sequence=4"});
  RunResult drives = run({"run", kGearboxDrives, "--set", "MAIN.sequence=4"});
  EXPECT_EQ(ideal.exitCode, 3) << show(ideal);
  EXPECT_TRUE(contains(ideal.out, collision)) << show(ideal);
  EXPECT_EQ(drives.exitCode, 3) << show(drives);
  EXPECT_TRUE(contains(drives.out, "Run ended     collision: robots collided in a shared zone")) << show(drives);
  EXPECT_TRUE(contains(drives.out, collision)) << show(drives);
}

class RunReport : public RunCommand {};

TEST_F(RunReport, GanttChartRendersInAHeadlessBrowser) {
  const std::string html = out("report.html");
  RunResult r = run({"run", kGearbox, "--set", "MAIN.sequence=3", "--report", html, "--signal", "Robot1.busy", "--signal",
                     "Robot2.busy", "--quiet"});
  ASSERT_EQ(r.exitCode, 0) << show(r);
  const std::string page = readFile(html);
  EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_TRUE(contains(page, "class=\"chart gantt\"")) << "no Gantt chart";
  EXPECT_TRUE(contains(page, "Energy per robot"));
  EXPECT_TRUE(contains(page, "Robot1.busy"));
  EXPECT_TRUE(contains(page, "Robot2.busy"));
  EXPECT_FALSE(contains(page, "<script")) << "the report is static HTML";

  if (::access(kChromium, X_OK) != 0) {
    const char* require = std::getenv("VIRTCOM_REQUIRE_BROWSER");
    if (require != nullptr && std::string(require) == "1")
      FAIL() << kChromium << " is not installed but VIRTCOM_REQUIRE_BROWSER=1: install chromium (the Makefile's "
             << "package list has it) to check the report in a real browser";
    GTEST_SKIP() << kChromium << " is not installed; the screenshot check is skipped";
  }
  const std::string png = out("report.png");
  const std::string profile = out("chromium-profile");
  fs::create_directories(profile);
  RunResult shot = exec("/usr/bin/timeout",
                        {"45", kChromium, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                         "--no-first-run", "--disable-background-networking", "--disable-component-update",
                         "--disable-sync", "--user-data-dir=" + profile, "--screenshot=" + png,
                         "--window-size=1400,1000", "file://" + html});
  ASSERT_TRUE(fs::exists(png)) << "chromium wrote no screenshot\n" << show(shot);
  const std::string bytes = readFile(png);
  EXPECT_GT(bytes.size(), 20u * 1024) << "a screenshot this small is a blank page";
  PngSize size = pngSize(bytes);
  ASSERT_TRUE(size.ok) << "not a PNG";
  EXPECT_EQ(size.width, 1400u);
  EXPECT_EQ(size.height, 1000u);
}

// The report's layout in Chromium at 1400 px (tests/e2e/hmi/check_report.js): no panel or card
// scrolls sideways and no chart label reaches outside its chart, for a device table too wide to
// sit beside the energy chart and a run of several cycles (issue 16).
TEST_F(RunReport, LayoutHoldsAt1400PxInChromium) {
  const std::string html = out("layout.html");
  RunResult r = run({"run", "cells/report_layout.yaml", "--report", html, "--json", out("layout.json")});
  ASSERT_EQ(r.exitCode, 0) << show(r);
  EXPECT_TRUE(contains(r.out, "Cycles        min ")) << show(r);
  EXPECT_TRUE(contains(readFile(out("layout.json")), "\"cycles\": [")) << "every cycle in the JSON";
  const std::string page = readFile(html);
  EXPECT_TRUE(contains(page, "id=\"cycles\"")) << "the cycles table";
  if (::access(kChromium, X_OK) != 0 || !fs::exists(std::string(VIRTCOM_HMI_CLIENT_DIR) + "/node_modules/playwright-core")) {
    const char* require = std::getenv("VIRTCOM_REQUIRE_BROWSER");
    if (require != nullptr && std::string(require) == "1")
      FAIL() << kChromium << " or npm playwright-core is missing: install chromium and run `npm ci --prefix tests/e2e/hmi`";
    GTEST_SKIP() << "no browser; the layout check is skipped";
  }
  RunResult check = exec("/usr/bin/timeout", {"60", "/usr/bin/env", "node", std::string(VIRTCOM_HMI_CLIENT_DIR) + "/check_report.js",
                                              html, work_.string()});
  EXPECT_EQ(check.exitCode, 0) << show(check);
  EXPECT_TRUE(contains(check.out, "report checks passed")) << show(check);
}

class RunLong : public RunCommand {};

// Bounded memory: signal changes stream to the --vcd/--csv files as the run goes, so a run four
// times as long (four times the file) needs no more memory. When every change was kept in memory
// this run's peak RSS grew by 5.5 MB from 300 s to 1200 s (Release); now by under 0.6 MB.
TEST_F(RunLong, MemoryDoesNotGrowWithSimulatedTime) {
  // In the sanitizer build, freed memory waits in AddressSanitizer's quarantine and counts as
  // resident: without it the children's RSS is the program's own.
  const char* asan = std::getenv("ASAN_OPTIONS");
  ::setenv("ASAN_OPTIONS", (std::string(asan ? asan : "") + ":quarantine_size_mb=0").c_str(), 1);
  // One backend for both: with `auto`, whether the compiled tier is loaded depends on the wall
  // time a run takes (half a second), not on the simulated time this test is about.
  const std::string cell = "cells/pressing_forever.yaml";
  RunResult shortRun = run({"run", cell, "--backend", "interp", "--time-limit", "300s", "--quiet", "--vcd", out("short.vcd"), "--csv",
                            out("short.csv")});
  RunResult longRun = run({"run", cell, "--backend", "interp", "--time-limit", "1200s", "--quiet", "--vcd", out("long.vcd"), "--csv",
                           out("long.csv")});
  EXPECT_EQ(shortRun.exitCode, 3) << show(shortRun);  // the time limit ends both runs
  EXPECT_EQ(longRun.exitCode, 3) << show(longRun);
  const auto shortBytes = fs::file_size(out("short.vcd")) + fs::file_size(out("short.csv"));
  const auto longBytes = fs::file_size(out("long.vcd")) + fs::file_size(out("long.csv"));
  EXPECT_GT(longBytes, 3 * shortBytes) << "the long run must do about four times the work";
  EXPECT_LT(longRun.maxRssKb - shortRun.maxRssKb, 2 * 1024) << shortRun.maxRssKb << " kB -> " << longRun.maxRssKb << " kB";
  if (asan) ::setenv("ASAN_OPTIONS", asan, 1);
  else ::unsetenv("ASAN_OPTIONS");
}

// The sum of the "Total" row's operations column of the summary table (every activity of the run,
// the elided ones included).
uint64_t totalOperations(const std::string& summary) {
  const size_t row = summary.find("\nTotal");
  if (row == std::string::npos) return 0;
  std::istringstream line(summary.substr(row + 1, summary.find('\n', row + 1) - row - 1));
  std::vector<std::string> words{std::istream_iterator<std::string>(line), std::istream_iterator<std::string>()};
  return words.size() >= 2 ? std::stoull(words[words.size() - 2]) : 0;  // ... operations errors
}

// Bounded memory with many activities (issue 21): the trace keeps the first and last of a long
// run's activities (docs/report.md "Long runs"), so a run with six times as many (a million) needs
// no more memory. When every activity was kept, the long run's peak RSS was 59 MB above the short
// one's (Release).
TEST_F(RunLong, MemoryDoesNotGrowWithTheNumberOfActivities) {
  const char* asan = std::getenv("ASAN_OPTIONS");
  ::setenv("ASAN_OPTIONS", (std::string(asan ? asan : "") + ":quarantine_size_mb=0").c_str(), 1);
  const std::string cell = "cells/many_presses.yaml";
  RunResult shortRun = run({"run", cell, "--time-limit", "100s"});
  RunResult longRun = run({"run", cell, "--time-limit", "600s"});
  EXPECT_EQ(shortRun.exitCode, 3) << show(shortRun);
  EXPECT_EQ(longRun.exitCode, 3) << show(longRun);
  const uint64_t shortOps = totalOperations(shortRun.out), longOps = totalOperations(longRun.out);
  constexpr uint64_t kDefaultWindow = 100'000;  // --trace-window (docs/report.md)
  EXPECT_GT(shortOps, kDefaultWindow) << show(shortRun);  // both runs are past the window
  EXPECT_GT(longOps, 5 * shortOps) << show(longRun);
  EXPECT_LT(longRun.maxRssKb - shortRun.maxRssKb, 2 * 1024) << shortRun.maxRssKb << " kB -> " << longRun.maxRssKb << " kB";
  // A window as large as the run keeps every activity: the same run grows by their 40 bytes each.
  RunResult unbounded = run({"run", cell, "--time-limit", "600s", "--quiet", "--trace-window", std::to_string(2 * longOps)});
  EXPECT_EQ(unbounded.exitCode, 3) << show(unbounded);
  EXPECT_GT(unbounded.maxRssKb - longRun.maxRssKb, 20 * 1024) << longRun.maxRssKb << " kB -> " << unbounded.maxRssKb << " kB";
  if (asan) ::setenv("ASAN_OPTIONS", asan, 1);
  else ::unsetenv("ASAN_OPTIONS");
}

}  // namespace
