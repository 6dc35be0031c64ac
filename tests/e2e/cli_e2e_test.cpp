// End-to-end tests of the `virtcom` command: each test runs the built binary (VIRTCOM_EXE) on
// files in tests/e2e/data and checks its exit code, stdout and stderr as a user sees them.
// The child runs with tests/e2e/data as its working directory, so diagnostics show the short
// relative file names; anything it writes (--trace-file) goes to a per-test temporary folder.
// Everything runs in virtual time except the --speed tests: one asserts no timing, the other
// only a gross overload (a scan 10 times its interval) against a scan with 50 ms to spare.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "support/read_file.hpp"

namespace fs = std::filesystem;

namespace {

using virtcom::test::readFile;

const char* const kExe = VIRTCOM_EXE;
const char* const kDataDir = VIRTCOM_E2E_DATA;

struct RunResult {
  int exitCode = -1;  // the process's exit status; 128 + signal if it was killed
  std::string out;
  std::string err;
};

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    work_ = fs::path(::testing::TempDir()) /
            ("virtcom_e2e_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
             std::to_string(::getpid()));
    fs::remove_all(work_);
    fs::create_directories(work_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(work_, ec);
  }

  // Runs `virtcom args...` in the data folder and waits for it.
  RunResult run(const std::vector<std::string>& args) {
    const std::string outPath = (work_ / "stdout.txt").string();
    const std::string errPath = (work_ / "stderr.txt").string();
    std::vector<std::string> all{kExe};
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
      ::execv(kExe, argv.data());
      ::_exit(127);
    }
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0) {
    }
    RunResult r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = readFile(outPath);
    r.err = readFile(errPath);
    return r;
  }

  fs::path work_;
};

std::string show(const RunResult& r) {
  return "exit " + std::to_string(r.exitCode) + "\n--- stdout ---\n" + r.out + "--- stderr ---\n" + r.err;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

class CliHelp : public CliTest {};

TEST_F(CliHelp, TopLevelListsTheSubcommands) {
  RunResult r = run({"--help"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_TRUE(contains(r.out, "Usage:")) << show(r);
  EXPECT_TRUE(contains(r.out, "check")) << show(r);
  EXPECT_TRUE(contains(r.out, "exec")) << show(r);
  EXPECT_TRUE(contains(r.out, "--version")) << show(r);
}

TEST_F(CliHelp, ExecListsEveryOption) {
  RunResult r = run({"exec", "--help"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  for (const char* option : {"files", "--cycles", "--cycle-time", "--set", "--print", "--trace", "--trace-file",
                             "--speed", "--budget", "--backend", "--stats", "--retain-file"})
    EXPECT_TRUE(contains(r.out, option)) << option << "\n" << show(r);
}

TEST_F(CliHelp, ServeListsEveryOption) {
  RunResult r = run({"serve", "--help"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  for (const char* option : {"cell", "--modbus", "--modbus-allow", "--ads", "--ads-netid", "--ads-allow",
                             "--ads-readonly", "--speed", "--backend", "--quiet", "--json"})
    EXPECT_TRUE(contains(r.out, option)) << option << "\n" << show(r);
}

TEST_F(CliHelp, MonitorListsEveryOption) {
  RunResult r = run({"monitor", "--help"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  for (const char* option : {"cell", "--ads", "--modbus", "--netid", "--poll", "--deviation", "--json", "--quiet", "--http", "--http-allow",
                             "--hmi-token", "--hmi-readonly", "--history", "--history-keep-days", "--history-max-mb", "--history-queue"})
    EXPECT_TRUE(contains(r.out, option)) << option << "\n" << show(r);
}

TEST_F(CliHelp, CheckDescribesItsFilesAndExitCodes) {
  RunResult r = run({"check", "--help"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_TRUE(contains(r.out, "files")) << show(r);
  EXPECT_TRUE(contains(r.out, "exit 0 clean, 1 on errors")) << show(r);
}

TEST_F(CliHelp, Version) {
  RunResult r = run({"--version"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, "virtcom 0.1.0\n");
}

// --backend aot: the same output and fault report as the interpreter; without a working C
// compiler a one-line notice, then the interpreter. Compiled modules go to the test's folder.
class CliBackend : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    ::setenv("VIRTCOM_AOT_CACHE", (work_ / "aot").c_str(), 1);
  }
  void TearDown() override {
    ::unsetenv("VIRTCOM_AOT_CACHE");
    ::unsetenv("CC");
    ::unsetenv("VIRTCOM_TIER_SWITCH_AT_SCAN");
    ::unsetenv("VIRTCOM_TIER_LOG");
    ::unsetenv("VIRTCOM_TIER_DELAY_MS");
    CliTest::TearDown();
  }
  // The files left in the AOT cache folder (compiled objects and their C source, or leftovers).
  std::vector<std::string> cacheFiles() {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(work_ / "aot", ec)) names.push_back(e.path().filename().string());
    return names;
  }
};

TEST_F(CliBackend, AotPrintsWhatTheInterpreterPrints) {
  const std::vector<std::string> args{"exec", "ton.st", "--cycles", "40", "--trace", "MAIN.q,MAIN.et"};
  std::vector<std::string> aot = args;
  aot.insert(aot.end(), {"--backend", "aot"});
  RunResult interp = run(args), compiled = run(aot);
  EXPECT_EQ(compiled.exitCode, 0) << show(compiled);
  EXPECT_EQ(compiled.out, interp.out) << show(compiled);
  EXPECT_FALSE(contains(compiled.err, "notice")) << show(compiled);
  EXPECT_TRUE(fs::exists(work_ / "aot")) << "nothing compiled";
}

TEST_F(CliBackend, AotReportsTheSameFault) {
  RunResult interp = run({"exec", "divzero.st", "--cycles", "5"});
  RunResult compiled = run({"exec", "divzero.st", "--cycles", "5", "--backend", "aot"});
  EXPECT_EQ(interp.exitCode, 2) << show(interp);
  EXPECT_EQ(compiled.exitCode, 2) << show(compiled);
  EXPECT_TRUE(contains(compiled.err, "division by zero at divzero.st:8:")) << show(compiled);
  EXPECT_EQ(compiled.err, interp.err);
  EXPECT_EQ(compiled.out, interp.out);
}

TEST_F(CliBackend, WithoutACompilerFallsBackToTheInterpreter) {
  ::setenv("CC", "virtcom-no-such-compiler", 1);
  RunResult r = run({"exec", "counter.st", "--cycles", "5", "--print", "MAIN.count", "--backend", "aot"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, "MAIN.count = 5\n");
  EXPECT_TRUE(contains(r.err, "notice: --backend aot unavailable, using the interpreter")) << show(r);
  EXPECT_TRUE(contains(r.err, "virtcom-no-such-compiler")) << show(r);
}

// --backend auto (the default) switches between two scans: forced after scan 7 of 40 (the test
// hook), the output is the interpreter's and the log line shows where it switched.
TEST_F(CliBackend, AutoSwitchingMidRunPrintsWhatTheInterpreterPrints) {
  const std::vector<std::string> args{"exec", "ton.st", "--cycles", "40", "--trace", "MAIN.q,MAIN.et"};
  std::vector<std::string> tiered = args, interp = args;
  tiered.insert(tiered.end(), {"--backend", "auto"});
  interp.insert(interp.end(), {"--backend", "interp"});
  ::setenv("VIRTCOM_TIER_LOG", "1", 1);
  RunResult reference = run(interp);
  ::setenv("VIRTCOM_TIER_SWITCH_AT_SCAN", "7", 1);
  RunResult r = run(tiered);
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, reference.out) << show(r);
  EXPECT_TRUE(contains(r.err, "tier: --backend auto: 7 scans interpreted, 33 on machine code, switched at 0.07 s"))
      << show(r);
  EXPECT_TRUE(contains(reference.err, "tier: --backend interp: 40 scans interpreted, 0 on machine code")) << show(reference);
}

// A former aot run leaves the program's machine code in the cache: the default auto then runs it
// from the first scan (found without generating C or compiling: no compiler is reachable) and
// prints what the interpreter prints; a changed program is not taken for it.
TEST_F(CliBackend, AutoRunsAFormerCompileFromTheFirstScan) {
  const std::vector<std::string> args{"exec", "ton.st", "--cycles", "40", "--trace", "MAIN.q,MAIN.et"};
  std::vector<std::string> aot = args, interp = args;
  aot.insert(aot.end(), {"--backend", "aot"});
  interp.insert(interp.end(), {"--backend", "interp"});
  RunResult reference = run(interp);
  ASSERT_EQ(run(aot).exitCode, 0);
  ::setenv("VIRTCOM_TIER_LOG", "1", 1);
  ::setenv("CC", "virtcom-no-such-compiler", 1);
  RunResult r = run(args);
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, reference.out) << show(r);
  EXPECT_TRUE(contains(r.err, "tier: --backend auto: 0 scans interpreted, 40 on machine code; machine code from the cache at load"))
      << show(r);
  RunResult other = run({"exec", "counter.st", "--cycles", "5", "--print", "MAIN.count"});
  EXPECT_EQ(other.out, "MAIN.count = 5\n");
  EXPECT_TRUE(contains(other.err, "tier: --backend auto: 5 scans interpreted, 0 on machine code")) << show(other);
}

// `--backend aot` serves a former compile from the cache only when the compiler of now made it: with
// $CC changed to a compiler that does not exist it falls back to the interpreter, as without a cache.
TEST_F(CliBackend, AotTakesCachedCodeOnlyFromTheSameCompiler) {
  const std::vector<std::string> args{"exec", "counter.st", "--cycles", "5", "--print", "MAIN.count", "--backend", "aot"};
  RunResult warm = run(args);
  ASSERT_EQ(warm.exitCode, 0) << show(warm);
  RunResult again = run(args);
  EXPECT_EQ(again.out, "MAIN.count = 5\n");
  EXPECT_EQ(again.err, "") << show(again);
  ::setenv("CC", "virtcom-no-such-compiler", 1);
  RunResult other = run(args);
  EXPECT_EQ(other.out, "MAIN.count = 5\n");
  EXPECT_TRUE(contains(other.err, "notice: --backend aot unavailable, using the interpreter")) << show(other);
}

// The default is auto; the same fault report as the interpreter after a switch before the faulting scan.
TEST_F(CliBackend, AutoIsTheDefaultAndReportsTheSameFault) {
  RunResult interp = run({"exec", "divzero.st", "--cycles", "5", "--backend", "interp"});
  ::setenv("VIRTCOM_TIER_SWITCH_AT_SCAN", "1", 1);
  ::setenv("VIRTCOM_TIER_LOG", "1", 1);
  RunResult tiered = run({"exec", "divzero.st", "--cycles", "5"});
  EXPECT_EQ(tiered.exitCode, 2) << show(tiered);
  EXPECT_TRUE(contains(tiered.err, "division by zero at divzero.st:8:")) << show(tiered);
  EXPECT_TRUE(contains(tiered.err, "tier: --backend auto: ")) << show(tiered);
  EXPECT_EQ(tiered.out, interp.out);
}

// Without a C compiler auto stays on the interpreter and says nothing.
TEST_F(CliBackend, AutoWithoutACompilerStaysQuietlyOnTheInterpreter) {
  ::setenv("CC", "virtcom-no-such-compiler", 1);
  ::setenv("VIRTCOM_TIER_SWITCH_AT_SCAN", "2", 1);  // compiled (and failed) before the first scan
  RunResult r = run({"exec", "counter.st", "--cycles", "5", "--print", "MAIN.count", "--backend", "auto"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, "MAIN.count = 5\n");
  EXPECT_EQ(r.err, "");
}

// A run that ends before the background compile does not wait for it: the compiler (here a
// script that would sleep for ten minutes) is terminated, and no temporary file stays in the
// cache. Were the exit to wait for the compiler, this test would hang until its time-out.
TEST_F(CliBackend, AutoDoesNotWaitForTheCompilerAndLeavesNoTemporaryFiles) {
  const fs::path compiler = work_ / "slow-cc.sh";
  const fs::path pidFile = work_ / "cc.pid";
  std::ofstream(compiler) << "#!/bin/sh\necho $$ > " << pidFile.string() << "\nexec sleep 600\n";
  fs::permissions(compiler, fs::perms::owner_all);
  ::setenv("CC", compiler.c_str(), 1);
  ::setenv("VIRTCOM_TIER_LOG", "1", 1);
  ::setenv("VIRTCOM_TIER_DELAY_MS", "0", 1);  // compile at once, however short the run
  RunResult r = run({"exec", "counter.st", "--cycles", "200000"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_TRUE(contains(r.err, "machine code not ready when the run ended")) << show(r);
  EXPECT_EQ(cacheFiles(), std::vector<std::string>{}) << "temporary files left in the cache";
  // The compiler (if it got as far as writing its pid) no longer runs: gone, or a zombie.
  std::ifstream pid(pidFile);
  std::string id;
  if (pid >> id) {
    const std::string stat = readFile(fs::path("/proc") / id / "stat");
    const size_t close = stat.rfind(')');
    EXPECT_TRUE(stat.empty() || (close != std::string::npos && stat.substr(close + 2, 1) == "Z")) << stat;
  }
}

TEST_F(CliBackend, UnknownBackendIsAUsageError) {
  RunResult r = run({"exec", "counter.st", "--backend", "jit"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_TRUE(contains(r.err, "--backend")) << show(r);
}

class CliUsage : public CliTest {};

TEST_F(CliUsage, UnknownOptionIsAnError) {
  RunResult r = run({"exec", "counter.st", "--bogus"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_TRUE(contains(r.err, "--bogus")) << show(r);
  EXPECT_EQ(r.out, "");
}

TEST_F(CliUsage, UnknownTopLevelOptionIsAnError) {
  RunResult r = run({"--frobnicate"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_TRUE(contains(r.err, "see virtcom --help")) << show(r);
  EXPECT_EQ(r.out, "");
}

// Regression test (was a bug found by the e2e/unit suites).
TEST_F(CliUsage, UnknownTopLevelOptionOrSubcommandIsNamed) {
  RunResult r = run({"--frobnicate"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_TRUE(contains(r.err, "--frobnicate")) << show(r);
  r = run({"frobnicate"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_TRUE(contains(r.err, "frobnicate")) << show(r);
}

TEST_F(CliUsage, MissingSubcommandIsAnError) {
  RunResult r = run({});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_TRUE(contains(r.err, "subcommand is required")) << show(r);
}

TEST_F(CliUsage, ExecWithoutFilesIsAnError) {
  RunResult r = run({"exec"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_TRUE(contains(r.err, "files")) << show(r);
}

TEST_F(CliUsage, NegativeCyclesAreRejected) {
  RunResult r = run({"exec", "counter.st", "--cycles", "-1"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_TRUE(contains(r.err, "--cycles")) << show(r);
}

TEST_F(CliUsage, ZeroSpeedIsRejected) {
  RunResult r = run({"exec", "counter.st", "--speed", "0"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_TRUE(contains(r.err, "--speed")) << show(r);
}

class CliCheck : public CliTest {};

TEST_F(CliCheck, CleanFileExitsZero) {
  RunResult r = run({"check", "counter.st"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.err, "ok: 1 file(s), no diagnostics\n");
  EXPECT_EQ(r.out, "");
}

TEST_F(CliCheck, ErrorsExitOneWithRenderedDiagnostics) {
  RunResult r = run({"check", "errors.st"});
  EXPECT_EQ(r.exitCode, 1) << show(r);
  EXPECT_EQ(r.err,
            "errors.st:6:6: error[E201]: 'b' is not declared\n"
            "  a := b + 1;\n"
            "       ^\n"
            "errors.st:7:6: error[E202]: type mismatch: cannot assign STRING(1) to INT\n"
            "  a := 'x';\n"
            "       ^\n"
            "2 error(s), 0 warning(s)\n");
  EXPECT_EQ(r.out, "");
}

TEST_F(CliCheck, WarningsAreShownButDoNotFail) {
  RunResult r = run({"check", "warning.st"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.err,
            "warning.st:6:20: warning[W302]: FOR with BY 0 never ends\n"
            "  FOR i := 1 TO 3 BY 0 DO\n"
            "                     ^\n"
            "0 error(s), 1 warning(s)\n");
}

TEST_F(CliCheck, SeveralFilesCompileTogether) {
  RunResult r = run({"check", "GVL.st", "uses_gvl.st"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.err, "ok: 2 file(s), no diagnostics\n");
}

TEST_F(CliCheck, MissingFileIsAnError) {
  RunResult r = run({"check", "no_such_file.st"});
  EXPECT_NE(r.exitCode, 0) << show(r);
  EXPECT_TRUE(contains(r.err, "no_such_file.st")) << show(r);
}

TEST_F(CliCheck, NoProgramIsAnErrorWhenRunning) {
  RunResult r = run({"exec", "no_program.st", "--cycles", "1"});
  EXPECT_EQ(r.exitCode, 1) << show(r);
  EXPECT_TRUE(contains(r.err, "error[E217]: no PROGRAM to run")) << show(r);
}

// Regression test (was a bug found by the e2e/unit suites).
TEST_F(CliCheck, NoProgramDoesNotBlameTheStandardLibrary) {
  RunResult r = run({"exec", "no_program.st", "--cycles", "1"});
  EXPECT_EQ(r.exitCode, 1) << show(r);
  EXPECT_FALSE(contains(r.err, "<standard library>")) << show(r);
}

// Library mode: files with only FUNCTIONs, FBs, types and GVLs are checked, not refused (E217).
TEST_F(CliCheck, FilesWithoutProgramAreCheckedAsALibrary) {
  RunResult r = run({"check", "no_program.st"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.err, "ok: 1 file(s), no diagnostics (a library: no PROGRAM)\n");
}

TEST_F(CliCheck, LibraryErrorsAreStillReported) {
  RunResult r = run({"check", "library_bad_init.st"});
  EXPECT_EQ(r.exitCode, 1) << show(r);
  EXPECT_TRUE(contains(r.err, "library_bad_init.st:4:19: error[E117]")) << show(r);
}

class CliExec : public CliTest {};

TEST_F(CliExec, PrintAfterCycles) {
  RunResult r = run({"exec", "counter.st", "--cycles", "5", "--print", "MAIN.count"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, "MAIN.count = 5\n");
  EXPECT_EQ(r.err, "");
}

// A program compiled once is read back from the module cache: the second run prints the same,
// leaves the cached module untouched; a program with a warning is never kept (its warning shows
// each time); VIRTCOM_MODULE_CACHE=off keeps nothing.
TEST_F(CliExec, TheSecondRunReadsTheCompiledModuleBack) {
  const fs::path cache = work_ / "modules";
  ::setenv("VIRTCOM_MODULE_CACHE", cache.c_str(), 1);
  const std::vector<std::string> args{"exec", "counter.st", "--cycles", "5", "--print", "MAIN.count", "--backend", "interp"};
  RunResult first = run(args);
  ASSERT_EQ(first.exitCode, 0) << show(first);
  std::vector<fs::path> kept;
  for (const auto& e : fs::directory_iterator(cache)) kept.push_back(e.path());
  ASSERT_EQ(kept.size(), 1u);
  const auto written = fs::last_write_time(kept[0]);
  RunResult second = run(args);
  EXPECT_EQ(second.out, first.out);
  EXPECT_EQ(second.err, first.err);
  EXPECT_EQ(fs::last_write_time(kept[0]), written);
  run({"exec", "warning.st", "--cycles", "1"});
  RunResult warnedAgain = run({"exec", "warning.st", "--cycles", "1"});
  EXPECT_TRUE(contains(warnedAgain.err, "warning[W302]")) << show(warnedAgain);
  EXPECT_EQ(std::distance(fs::directory_iterator(cache), fs::directory_iterator()), 1);
  ::setenv("VIRTCOM_MODULE_CACHE", "off", 1);
  fs::remove_all(cache);
  EXPECT_EQ(run(args).out, first.out);
  EXPECT_FALSE(fs::exists(cache));
  ::unsetenv("VIRTCOM_MODULE_CACHE");
}

TEST_F(CliExec, RetainFileGivesAWarmStart) {
  const std::string file = (work_ / "retain.txt").string();
  const std::vector<std::string> args{"exec", "retain.st", "--cycles", "3", "--retain-file", file, "--print", "MAIN.total",
                                      "--print", "MAIN.scans", "--print", "gRuns", "--print", "MAIN.history", "--print", "gName"};
  RunResult first = run(args);
  EXPECT_EQ(first.exitCode, 0) << show(first);
  EXPECT_EQ(first.out, "MAIN.total = 3\nMAIN.scans = 3\ngRuns = 1\nMAIN.history = [0, 1]\ngName = 'run1'\n");
  RunResult second = run(args);
  EXPECT_EQ(second.exitCode, 0) << show(second);
  EXPECT_EQ(second.out, "MAIN.total = 6\nMAIN.scans = 3\ngRuns = 2\nMAIN.history = [1, 2]\ngName = 'run2'\n");
  // Globals are saved under their qualified names: retain.st's globals form the list 'retain'.
  const std::string saved = readFile(file);
  EXPECT_TRUE(contains(saved, "retain.gRuns 0200 INT\n")) << saved;
  EXPECT_TRUE(contains(saved, "MAIN.total 06000000 DINT\n")) << saved;
}

TEST_F(CliExec, RetainFileSkipsVariablesWhoseTypeChanged) {
  const std::string file = (work_ / "retain.txt").string();
  {
    std::ofstream out(file);
    out << "MAIN.total 0500000000000000 LINT\nretain.gRuns 0700 INT\nMAIN.gone 01 BOOL\n";
  }
  RunResult r = run({"exec", "retain.st", "--cycles", "1", "--retain-file", file, "--print", "MAIN.total", "--print", "gRuns"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, "MAIN.total = 1\ngRuns = 8\n");
}

TEST_F(CliExec, MalformedRetainFileIsAnError) {
  const std::string file = (work_ / "retain.txt").string();
  {
    std::ofstream out(file);
    out << "gRuns zz INT\n";
  }
  RunResult r = run({"exec", "retain.st", "--retain-file", file});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_TRUE(contains(r.err, "retain.txt:1: expected NAME HEX TYPE")) << show(r);
}

// FB_exit (issue 16) runs after the last scan and before --print and the retain file.
TEST_F(CliExec, FbExitRunsOnceWhenTheProgramEnds) {
  const std::string file = (work_ / "retain.txt").string();
  const std::vector<std::string> args{"exec", "fb_exit.st", "--cycles", "3", "--retain-file", file,
                                      "--print", "MAIN.scans", "--print", "MAIN.journal.closed", "--print", "gShutdowns"};
  RunResult first = run(args);
  EXPECT_EQ(first.exitCode, 0) << show(first);
  EXPECT_EQ(first.out, "MAIN.scans = 3\nMAIN.journal.closed = TRUE\ngShutdowns = 1\n");
  RunResult second = run(args);
  EXPECT_EQ(second.exitCode, 0) << show(second);
  EXPECT_EQ(second.out, "MAIN.scans = 3\nMAIN.journal.closed = TRUE\ngShutdowns = 2\n");
}

TEST_F(CliExec, FaultInFbExitIsARuntimeFault) {
  RunResult r = run({"exec", "fb_exit_fault.st", "--cycles", "2", "--print", "MAIN.stats.mean"});
  EXPECT_EQ(r.exitCode, 2) << show(r);
  EXPECT_TRUE(contains(r.err, "runtime fault in FB_exit: division by zero at fb_exit_fault.st:9:")) << show(r);
}

TEST_F(CliExec, DefaultIsOneCycle) {
  RunResult r = run({"exec", "counter.st", "--print", "MAIN.count"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, "MAIN.count = 1\n");
}

TEST_F(CliExec, ZeroCyclesShowsInitialValues) {
  RunResult r = run({"exec", "set_before_scan.st", "--cycles", "0", "--print", "MAIN.maxCount"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, "MAIN.maxCount = 3\n");
}

TEST_F(CliExec, PrintNamesAreCaseInsensitiveAndEchoedAsTyped) {
  RunResult r = run({"exec", "ton.st", "--print", "main.Q", "--print", "MAIN.t"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out,
            "main.Q = FALSE\n"
            "MAIN.t = (IN := TRUE, PT := T#100ms, Q := FALSE, ET := T#0ms)\n");
}

TEST_F(CliExec, PrintUnknownVariableIsAnError) {
  RunResult r = run({"exec", "counter.st", "--print", "MAIN.nosuch"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_EQ(r.err, "error: unknown variable 'MAIN.nosuch' (use the qualified name, e.g. MAIN.count or GVL.x)\n");
  EXPECT_EQ(r.out, "");
}

TEST_F(CliExec, SetAppliesBeforeTheFirstScan) {
  RunResult r = run({"exec", "set_before_scan.st", "--cycles", "10", "--set", "MAIN.maxCount=7", "--print",
                     "MAIN.firstSeen", "--print", "MAIN.count"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, "MAIN.firstSeen = 7\nMAIN.count = 7\n");
}

TEST_F(CliExec, SetIsRepeatableAndParsesIecLiterals) {
  RunResult r = run({"exec", "set_before_scan.st", "--cycles", "0", "--set", "MAIN.maxCount=16#10", "--set",
                     "MAIN.speed=1.5", "--set", "MAIN.mode='manual'", "--print", "MAIN.maxCount", "--print",
                     "MAIN.speed", "--print", "MAIN.mode"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, "MAIN.maxCount = 16\nMAIN.speed = 1.5\nMAIN.mode = 'manual'\n");
}

TEST_F(CliExec, SetUnknownVariableIsAnError) {
  RunResult r = run({"exec", "set_before_scan.st", "--set", "MAIN.nosuch=1", "--print", "MAIN.count"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_EQ(r.err, "error: --set unknown variable 'MAIN.nosuch' (use the qualified name, e.g. MAIN.count or GVL.x)\n");
  EXPECT_EQ(r.out, "");  // nothing ran, nothing printed
}

TEST_F(CliExec, SetBadValueIsAnError) {
  RunResult r = run({"exec", "set_before_scan.st", "--set", "MAIN.maxCount=abc"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_EQ(r.err, "error: --set MAIN.maxCount: invalid INT literal 'abc'\n");
}

TEST_F(CliExec, SetOutOfRangeValueIsAnError) {
  RunResult r = run({"exec", "set_before_scan.st", "--set", "MAIN.maxCount=70000"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_EQ(r.err, "error: --set MAIN.maxCount: value 70000 out of range for INT (-32768..32767)\n");
}

TEST_F(CliExec, SetWithoutEqualsIsAnError) {
  RunResult r = run({"exec", "set_before_scan.st", "--set", "MAIN.maxCount"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_EQ(r.err, "error: --set expected NAME=VALUE, found 'MAIN.maxCount'\n");
}

// Regression test (was a bug found by the e2e/unit suites).
TEST_F(CliExec, SetOnAConstantIsRefused) {
  RunResult r = run({"exec", "constant_and_input.st", "--set", "MAIN.k=9", "--print", "MAIN.y"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_TRUE(contains(r.err, "MAIN.k")) << show(r);
}

// Regression test (was a bug found by the e2e/unit suites).
TEST_F(CliExec, SetOnALocatedInputIsNotSilentlyLost) {
  // the value goes into the input image, so the scan's input copy keeps it
  RunResult r = run({"exec", "constant_and_input.st", "--set", "MAIN.button=TRUE", "--print", "MAIN.seenButton"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, "MAIN.seenButton = TRUE\n") << show(r);
}

TEST_F(CliExec, TraceWritesCsvHeaderAndOneRowPerScan) {
  RunResult r = run({"exec", "trace.st", "--cycles", "3", "--trace", "MAIN.a,MAIN.b"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out,
            "scan,time_ms,MAIN.a,MAIN.b\n"
            "0,0,2,TRUE\n"
            "1,10,4,FALSE\n"
            "2,20,6,TRUE\n");
}

TEST_F(CliExec, TraceIsRepeatableAndQuotesValuesWithCommas) {
  RunResult r = run({"exec", "trace.st", "--cycles", "2", "--trace", "MAIN.a", "--trace", "MAIN.pair,MAIN.s"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out,
            "scan,time_ms,MAIN.a,MAIN.pair,MAIN.s\n"
            "0,0,2,\"[1, 2]\",'it$'s'\n"
            "1,10,4,\"[1, 2]\",'it$'s'\n");
}

TEST_F(CliExec, TraceWithZeroCyclesIsJustTheHeader) {
  RunResult r = run({"exec", "trace.st", "--cycles", "0", "--trace", "MAIN.a"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, "scan,time_ms,MAIN.a\n");
}

TEST_F(CliExec, TraceUnknownVariableIsAnError) {
  RunResult r = run({"exec", "trace.st", "--trace", "MAIN.a,MAIN.nope"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_TRUE(contains(r.err, "unknown variable 'MAIN.nope'")) << show(r);
  EXPECT_EQ(r.out, "");
}

TEST_F(CliExec, TraceFileGetsTheCsvAndStdoutKeepsThePrints) {
  fs::path csv = work_ / "out.csv";
  RunResult r = run({"exec", "trace.st", "--cycles", "3", "--trace", "MAIN.a,MAIN.b", "--trace-file", csv.string(),
                     "--print", "MAIN.a"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, "MAIN.a = 6\n");
  ASSERT_TRUE(fs::exists(csv));
  EXPECT_EQ(readFile(csv),
            "scan,time_ms,MAIN.a,MAIN.b\n"
            "0,0,2,TRUE\n"
            "1,10,4,FALSE\n"
            "2,20,6,TRUE\n");
}

TEST_F(CliExec, TraceFileThatCannotBeWrittenIsAnError) {
  fs::path csv = work_ / "no_such_dir" / "out.csv";
  RunResult r = run({"exec", "trace.st", "--trace", "MAIN.a", "--trace-file", csv.string()});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_EQ(r.err, "error: cannot write " + csv.string() + "\n");
}

TEST_F(CliExec, DefaultCycleTimeIsTenMilliseconds) {
  RunResult r = run({"exec", "ton.st", "--cycles", "10", "--print", "MAIN.q", "--print", "MAIN.et"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, "MAIN.q = FALSE\nMAIN.et = T#90ms\n");
  r = run({"exec", "ton.st", "--cycles", "11", "--print", "MAIN.q"});
  EXPECT_EQ(r.out, "MAIN.q = TRUE\n");
}

TEST_F(CliExec, CycleTimeChangesTimerTiming) {
  RunResult r = run({"exec", "ton.st", "--cycles", "3", "--cycle-time", "50ms", "--trace", "MAIN.q,MAIN.et"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out,
            "scan,time_ms,MAIN.q,MAIN.et\n"
            "0,0,FALSE,T#0ms\n"
            "1,50,FALSE,T#50ms\n"
            "2,100,TRUE,T#100ms\n");
}

TEST_F(CliExec, CycleTimeAcceptsIecAndBareForms) {
  for (const char* form : {"T#50ms", "t#50MS", "0.05s", "50", "50000us"}) {
    RunResult r = run({"exec", "ton.st", "--cycles", "3", "--cycle-time", form, "--print", "MAIN.et"});
    EXPECT_EQ(r.exitCode, 0) << form << "\n" << show(r);
    EXPECT_EQ(r.out, "MAIN.et = T#100ms\n") << form;
  }
}

TEST_F(CliExec, BadCycleTimeIsAnError) {
  RunResult r = run({"exec", "ton.st", "--cycle-time", "fast"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_EQ(r.err, "error: --cycle-time: 'fast' is not a duration (e.g. 10ms, 1s, 250us)\n");
  r = run({"exec", "ton.st", "--cycle-time", "0ms"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
}

// Regression test (was a bug found by the e2e/unit suites).
TEST_F(CliExec, CycleTimeThatRoundsToZeroIsRejected) {
  RunResult r = run({"exec", "counter.st", "--cycle-time", "0.1ns", "--cycles", "3", "--print", "MAIN.count"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
}

// Regression test (was a bug found by the e2e/unit suites).
TEST_F(CliExec, CycleTimeWithAMalformedNumberIsRejected) {
  RunResult r = run({"exec", "counter.st", "--cycle-time", "1.2.3ms"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_TRUE(contains(r.err, "--cycle-time")) << show(r);
}

TEST_F(CliExec, CycleTimeLeavesConfiguredTasksAlone) {
  RunResult r = run({"exec", "two_tasks.st", "--cycles", "7", "--cycle-time", "50ms", "--print", "f.runs", "--print",
                     "s.runs", "--trace", "f.runs"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_TRUE(r.out.starts_with("scan,time_ms,f.runs\n0,0,1\n1,10,2\n")) << show(r);
  EXPECT_TRUE(r.out.ends_with("6,60,7\nf.runs = 7\ns.runs = 3\n")) << show(r);
}

TEST_F(CliExec, StatsGoToStderr) {
  RunResult r = run({"exec", "two_tasks.st", "--cycles", "7", "--stats"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, "");
  EXPECT_TRUE(contains(r.err, "task fast: 7 scans, exec min/avg/max ")) << show(r);
  EXPECT_TRUE(contains(r.err, "task slow: 3 scans, exec min/avg/max ")) << show(r);
}

TEST_F(CliExec, SeveralFilesRunAsOneProgram) {
  RunResult r = run({"exec", "GVL.st", "uses_gvl.st", "--cycles", "4", "--print", "GVL.total"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, "GVL.total = 40\n");
}

TEST_F(CliExec, RuntimeFaultExitsTwoAndNamesTheLocation) {
  RunResult r = run({"exec", "divzero.st", "--cycles", "10", "--trace", "MAIN.q", "--print", "MAIN.divisor"});
  EXPECT_EQ(r.exitCode, 2) << show(r);
  EXPECT_EQ(r.err, "runtime fault: division by zero at divzero.st:8:1 (task MainTask)\n");
  // the rows of the scans before the fault, then the values as the fault left them
  EXPECT_EQ(r.out,
            "scan,time_ms,MAIN.q\n"
            "0,0,50\n"
            "1,10,100\n"
            "MAIN.divisor = 0\n");
}

TEST_F(CliExec, WatchdogStopsAnEndlessLoop) {
  RunResult r = run({"exec", "endless.st", "--budget", "10000"});
  EXPECT_EQ(r.exitCode, 2) << show(r);
  EXPECT_TRUE(r.err.starts_with("runtime fault: watchdog: instruction budget exhausted at endless.st:")) << show(r);
  EXPECT_TRUE(r.err.ends_with("(task MainTask)\n")) << show(r);
}

TEST_F(CliExec, CompileErrorExitsOne) {
  RunResult r = run({"exec", "errors.st", "--print", "MAIN.a"});
  EXPECT_EQ(r.exitCode, 1) << show(r);
  EXPECT_TRUE(contains(r.err, "errors.st:6:6: error[E201]: 'b' is not declared\n")) << show(r);
  EXPECT_EQ(r.out, "");
}

TEST_F(CliExec, WarningsArePrintedAndTheProgramStillRuns) {
  RunResult r = run({"exec", "warning.st", "--cycles", "0", "--print", "MAIN.i"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, "MAIN.i = 0\n");
  EXPECT_TRUE(contains(r.err, "warning[W302]")) << show(r);
}

TEST_F(CliExec, MissingFileIsAnError) {
  RunResult r = run({"exec", "no_such_file.st", "--print", "MAIN.count"});
  EXPECT_NE(r.exitCode, 0) << show(r);
  EXPECT_TRUE(contains(r.err, "no_such_file.st")) << show(r);
  EXPECT_EQ(r.out, "");
}

TEST_F(CliExec, SpeedPacesButFinishes) {
  // 3 ticks of 10 ms at 1000x real time: about 20 us of wall time. No timing is asserted.
  RunResult r = run({"exec", "counter.st", "--speed", "1000", "--cycles", "3", "--print", "MAIN.count"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, "MAIN.count = 3\n");
}

// A paced run counts the ticks that started late (the scan before overran the interval) and says
// so at the end: an overloaded program at 1 ms starts nearly every tick late, a light one at
// 50 ms none (docs/performance.md, Late ticks).
TEST_F(CliExec, APacedRunCountsTheTicksThatStartedLate) {
  // The interpreter: under `auto` a native compile left in the cache by an earlier run makes the
  // scan short enough to start every tick on time.
  RunResult heavy = run({"exec", "overloaded.st", "--cycle-time", "1ms", "--speed", "1", "--cycles", "20", "--backend", "interp"});
  EXPECT_EQ(heavy.exitCode, 0) << show(heavy);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(heavy.err, m, std::regex(R"(timing: (\d+) of 20 ticks started late \(at most [0-9.]+ ms\)\n)")))
      << show(heavy);
  EXPECT_GE(std::stoi(m[1]), 15) << "the first tick has no period before it; the others overran: " << show(heavy);
  RunResult light = run({"exec", "counter.st", "--cycle-time", "50ms", "--speed", "1", "--cycles", "6"});
  EXPECT_EQ(light.exitCode, 0) << show(light);
  EXPECT_NE(light.err.find("timing: none of 6 ticks started late\n"), std::string::npos) << show(light);
}

TEST_F(CliExec, TraceStepsPrintsTheActiveStepsOfEveryScan) {
  RunResult r = run({"exec", "sfc_figure8.st", "--cycles", "7", "--trace-steps"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out,
            "scan 0 (0 ms): MAIN.Init\n"
            "scan 1 (10 ms): MAIN.Init\n"
            "scan 2 (20 ms): MAIN.Step2_1 MAIN.Step2_2\n"
            "scan 3 (30 ms): MAIN.Step2_1 MAIN.Step2_2\n"
            "scan 4 (40 ms): MAIN.Step2_1 MAIN.Step2_2\n"
            "scan 5 (50 ms): MAIN.Init\n"
            "scan 6 (60 ms): MAIN.Init\n");
}

TEST_F(CliExec, StepFlagsAndTimesArePrintableLikeVariables) {
  RunResult r = run({"exec", "sfc_figure8.st", "--cycles", "5", "--print", "MAIN.Step2_1.X", "--print", "MAIN.step2_2.t",
                     "--trace", "MAIN.Init.X"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out,
            "scan,time_ms,MAIN.Init.X\n"
            "0,0,TRUE\n"
            "1,10,TRUE\n"
            "2,20,FALSE\n"
            "3,30,FALSE\n"
            "4,40,FALSE\n"
            "MAIN.Step2_1.X = TRUE\n"
            "MAIN.step2_2.t = T#20ms\n");
}

TEST_F(CliExec, TraceStepsWithoutAChartIsAnError) {
  RunResult r = run({"exec", "counter.st", "--trace-steps"});
  EXPECT_EQ(r.exitCode, 64) << show(r);
  EXPECT_TRUE(contains(r.err, "--trace-steps: the program has no SFC steps")) << show(r);
  EXPECT_EQ(r.out, "");
}

TEST_F(CliHelp, ExecDescribesTraceSteps) {
  RunResult r = run({"exec", "--help"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_TRUE(contains(r.out, "--trace-steps")) << show(r);
}

// PLCopen TC6 XML projects (tests/golden/plcopen) go through check, exec and export like ST.
class CliPlcopen : public CliTest {};

TEST_F(CliPlcopen, ExecRunsALadderProject) {
  RunResult r = run({"exec", "../../golden/plcopen/beremiz_ld.xml", "--cycles", "3", "--set", "inst0.start=TRUE",
                     "--print", "inst0.motor", "--print", "inst0.count"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, "inst0.motor = TRUE\ninst0.count = 3\n");
}

TEST_F(CliPlcopen, CheckReportsTheXmlElement) {
  RunResult r = run({"check", "../../golden/plcopen/errors/network_errors.xml"});
  EXPECT_EQ(r.exitCode, 1) << show(r);
  EXPECT_TRUE(contains(r.err, "network_errors.xml:19:53: error[X006]: contact (localId 2)")) << show(r);
}

TEST_F(CliPlcopen, ExportedStProgramChecksAndRunsAsXml) {
  std::string out = (work_ / "counter.xml").string();
  RunResult r = run({"export", "--plcopen", out, "counter.st"});
  ASSERT_EQ(r.exitCode, 0) << show(r);
  std::string xml = readFile(out);
  EXPECT_TRUE(contains(xml, "<project xmlns=\"http://www.plcopen.org/xml/tc6_0201\"")) << xml;
  EXPECT_TRUE(contains(xml, "<pou name=\"MAIN\" pouType=\"program\">")) << xml;
  r = run({"exec", out, "--cycles", "4", "--print", "MAIN.count"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, "MAIN.count = 4\n");
}

// A textual SFC chart is exported as a graphical chart; the XML runs with the same steps.
TEST_F(CliPlcopen, ExportedSfcChartTracesTheSameSteps) {
  std::string out = (work_ / "figure8.xml").string();
  RunResult r = run({"export", "--plcopen", out, "sfc_figure8.st"});
  ASSERT_EQ(r.exitCode, 0) << show(r);
  std::string xml = readFile(out);
  EXPECT_TRUE(contains(xml, "<step localId=\"1\" name=\"Init\" initialStep=\"true\">")) << xml;
  EXPECT_TRUE(contains(xml, "<simultaneousDivergence")) << xml;
  RunResult st = run({"exec", "sfc_figure8.st", "--cycles", "8", "--trace-steps"});
  RunResult fromXml = run({"exec", out, "--cycles", "8", "--trace-steps"});
  ASSERT_EQ(st.exitCode, 0) << show(st);
  ASSERT_EQ(fromXml.exitCode, 0) << show(fromXml);
  EXPECT_TRUE(contains(st.out, "MAIN.Step2_1 MAIN.Step2_2")) << show(st);
  EXPECT_EQ(fromXml.out, st.out);
}

// Macro steps run as the steps they expand to, named Macro__Step (sfc_macro_step.xml).
TEST_F(CliPlcopen, MacroStepsAreTracedAsTheirExpandedSteps) {
  RunResult r = run({"exec", "../../golden/plcopen/sfc_macro_step.xml", "--cycles", "4", "--set", "tank.go=TRUE",
                     "--set", "tank.full=TRUE", "--trace-steps"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out,
            "scan 0 (0 ms): tank.Idle\n"
            "scan 1 (10 ms): tank.Fill__Open\n"
            "scan 2 (20 ms): tank.Fill__Dose__Pump\n"
            "scan 3 (30 ms): tank.Fill__Dose__Pump\n");
}

// Conditions wired from LD contacts, an FBD function and a TON of the SFC body (sfc_conditions.xml):
// the TON (T#30ms) is called from scan 7 on, while S6 is active, and clears the transition in scan 10.
TEST_F(CliPlcopen, WiredTransitionConditionsFireWhenTheirNetworkIsTrue) {
  RunResult r = run({"exec", "../../golden/plcopen/sfc_conditions.xml", "--cycles", "12", "--set", "seq.start=TRUE",
                     "--set", "seq.a=TRUE", "--set", "seq.level=3", "--set", "seq.ready=TRUE", "--set", "seq.b=TRUE",
                     "--set", "seq.pressure=6", "--trace-steps"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_TRUE(contains(r.out, "scan 5 (50 ms): seq.S5\nscan 6 (60 ms): seq.S6\n")) << show(r);
  EXPECT_TRUE(contains(r.out, "scan 9 (90 ms): seq.S6\nscan 10 (100 ms): seq.S7\n")) << show(r);
}

// A ladder program in XML and an ST function block checked together (as a cell's sources).
TEST_F(CliPlcopen, CheckAcceptsXmlAndStMixed) {
  RunResult r = run({"check", "cells/ld_handshake.xml", "cells/edge_counter.st"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  r = run({"exec", "cells/ld_handshake.xml", "cells/edge_counter.st", "--cycles", "2", "--print", "MAIN.starts.count"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_EQ(r.out, "MAIN.starts.count = 1\n");
}

TEST_F(CliPlcopen, ExportsALibraryWithoutProgram) {
  std::string out = (work_ / "library.xml").string();
  RunResult r = run({"export", "--plcopen", out, "no_program.st"});
  ASSERT_EQ(r.exitCode, 0) << show(r);
  EXPECT_TRUE(contains(readFile(out), "<pou name=\"Twice\" pouType=\"function\">")) << readFile(out);
}

TEST_F(CliPlcopen, ExportRefusesAProgramWithErrors) {
  std::string out = (work_ / "bad.xml").string();
  RunResult r = run({"export", "--plcopen", out, "errors.st"});
  EXPECT_EQ(r.exitCode, 1) << show(r);
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(CliHelp, ExportDescribesItsOptions) {
  RunResult r = run({"export", "--help"});
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_TRUE(contains(r.out, "--plcopen")) << show(r);
  EXPECT_TRUE(contains(r.out, "--name")) << show(r);
}

}  // namespace

// TwinCAT 3 source files (tests/e2e/data/twincat: a POU with FB_init, a method, a property and
// an action, a program, an interface, a DUT and a GVL written with CRLF) are read as the ST in
// their CDATA sections; diagnostics point into the XML file.
class CliTwinCat : public CliTest {
 protected:
  const std::vector<std::string> files_{"twincat/MAIN.TcPOU", "twincat/FB_Station.TcPOU", "twincat/I_Resettable.TcIO",
                                        "twincat/E_Mode.TcDUT", "twincat/GVL_Cell.TcGVL"};

  // The project with one file replaced by `text`, written to the test's folder.
  std::vector<std::string> withFile(const std::string& name, const std::string& text) {
    std::vector<std::string> out;
    for (const auto& f : files_) {
      if (fs::path(f).filename() != name) {
        out.push_back(f);
        continue;
      }
      out.push_back((work_ / name).string());
      std::ofstream(out.back(), std::ios::binary) << text;
    }
    return out;
  }

  static std::string replaced(std::string text, const std::string& from, const std::string& to) {
    size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
  }
};

TEST_F(CliTwinCat, ExecRunsTheProject) {
  std::vector<std::string> args{"exec"};
  args.insert(args.end(), files_.begin(), files_.end());
  for (const char* a : {"--cycles", "7", "--print", "MAIN.fbStation.nParts", "--print", "MAIN.bResetDone", "--print",
                        "MAIN.fbStation.eMode"})
    args.push_back(a);
  RunResult r = run(args);
  EXPECT_EQ(r.exitCode, 0) << show(r);
  // Counts to the limit bound by FB_init (3), is reset through the interface in scan 5, counts on.
  EXPECT_EQ(r.out, "MAIN.fbStation.nParts = 2\nMAIN.bResetDone = TRUE\nMAIN.fbStation.eMode = E_Mode#Running\n");
}

TEST_F(CliTwinCat, AnErrorInAnActionPointsAtItsLineInTheXml) {
  std::string pou = readFile(fs::path(kDataDir) / "twincat/FB_Station.TcPOU");
  std::vector<std::string> args{"check"};
  for (const auto& f : withFile("FB_Station.TcPOU", replaced(pou, "nParts := nParts + 1;", "nParts := nParts + ;")))
    args.push_back(f);
  RunResult r = run(args);
  EXPECT_EQ(r.exitCode, 1) << show(r);
  EXPECT_TRUE(contains(r.err, "FB_Station.TcPOU:58:41: error[E006]: expected an expression, found ';'")) << show(r);
  EXPECT_TRUE(contains(r.err, "<ST><![CDATA[nParts := nParts + ;]]></ST>")) << show(r);
}

TEST_F(CliTwinCat, AnErrorInACrlfFileKeepsItsColumn) {
  std::string gvl = readFile(fs::path(kDataDir) / "twincat/GVL_Cell.TcGVL");
  ASSERT_TRUE(contains(gvl, "\r\n"));
  std::vector<std::string> args{"check"};
  for (const auto& f : withFile("GVL_Cell.TcGVL", replaced(gvl, "BOOL := TRUE", "BOOL := 5 TRUE"))) args.push_back(f);
  RunResult r = run(args);
  EXPECT_EQ(r.exitCode, 1) << show(r);
  EXPECT_TRUE(contains(r.err, "GVL_Cell.TcGVL:6:23: error[E006]: expected ';' after variable declaration")) << show(r);
}

TEST_F(CliTwinCat, AGraphicalBodyIsNamedNotRead) {
  std::string pou = readFile(fs::path(kDataDir) / "twincat/FB_Station.TcPOU");
  std::vector<std::string> args{"check"};
  for (const auto& f :
       withFile("FB_Station.TcPOU", replaced(pou, "<ST><![CDATA[nParts := nParts + 1;]]></ST>", "<LD>...</LD>")))
    args.push_back(f);
  RunResult r = run(args);
  EXPECT_EQ(r.exitCode, 1) << show(r);
  EXPECT_TRUE(contains(r.err, "FB_Station.TcPOU:58:9: error[X004]: Action 'Count' is written in LD")) << show(r);
}

TEST_F(CliTwinCat, AFileThatIsNotTwinCatIsRefused) {
  std::vector<std::string> args{"check"};
  for (const auto& f : withFile("E_Mode.TcDUT", "<project/>\n")) args.push_back(f);
  RunResult r = run(args);
  EXPECT_EQ(r.exitCode, 1) << show(r);
  EXPECT_TRUE(contains(r.err, "E_Mode.TcDUT:1:1: error[X002]: the root element is <project>")) << show(r);
}

TEST_F(CliTwinCat, ATaskFileIsAWarningNotAnError) {
  std::string task = (work_ / "PlcTask.TcTTO").string();
  std::ofstream(task) << "<?xml version=\"1.0\"?>\n<TcPlcObject>\n  <Task Name=\"PlcTask\">\n"
                         "    <CycleTime>10000</CycleTime>\n  </Task>\n</TcPlcObject>\n";
  std::vector<std::string> args{"check"};
  args.insert(args.end(), files_.begin(), files_.end());
  args.push_back(task);
  RunResult r = run(args);
  EXPECT_EQ(r.exitCode, 0) << show(r);
  EXPECT_TRUE(contains(r.err, "PlcTask.TcTTO:3:3: warning[X101]: Task 'PlcTask': TwinCAT task settings are not read"))
      << show(r);
}
