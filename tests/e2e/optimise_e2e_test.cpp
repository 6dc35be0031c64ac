// End-to-end tests of `virtcom optimise`: the built binary (VIRTCOM_EXE) on the gearbox example's
// process model with a small budget, checked on its exit code, output and files as a user sees
// them; a model with a mistake; the same result with one and two threads; `virtcom sweep` on the
// gearbox, its slices merged (CSV and SQLite), its page, its Slurm script; the same results over
// MPI ranks (mpirun) as in one process.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>

#include "history/sqlite.hpp"
#include "shell_command.hpp"
#include "support/read_file.hpp"

namespace fs = std::filesystem;

namespace {

const std::string kExe = VIRTCOM_EXE;
const std::string kModel = std::string(VIRTCOM_SOURCE_DIR) + "/examples/gearbox-cell/process.yaml";

fs::path tempDir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("virtcom_optimise_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// Seconds of the first "found: best-1" row of the comparison table.
double bestCycle(const std::string& out) {
  std::smatch m;
  if (!std::regex_search(out, m, std::regex(R"(\| found: best-1 \| ([0-9.]+) \|)"))) return -1;
  return std::stod(m[1]);
}

TEST(Optimise, GearboxFindsAFeasibleSequenceAtLeastAsShortAsTheBestHandMadeOne) {
  const fs::path out = tempDir("gearbox");
  std::string text;
  int rc = virtcom::e2e::shell(kExe + " optimise " + kModel + " --budget-evals 40 --jobs 2 --quiet --out " + out.string(), text);
  ASSERT_EQ(rc, 0) << text;
  EXPECT_NE(text.find("method: exhaustive (24 distinct candidates"), std::string::npos) << text;
  EXPECT_NE(text.find("every distinct candidate was evaluated"), std::string::npos) << text;
  EXPECT_NE(text.find("| yours: 3 refined | 70.950 |"), std::string::npos) << text;
  EXPECT_NE(text.find("| yours: 4 naive | - | - | infeasible: collision at 33.280 s"), std::string::npos) << text;
  const double best = bestCycle(text);
  EXPECT_GT(best, 0) << text;
  EXPECT_LE(best, 70.950) << text;
  const std::string st = virtcom::test::readFile((out / "best-1.st").string());
  EXPECT_NE(st.find("jobs : ARRAY [1..48] OF ST_Job := ["), std::string::npos) << st;
  EXPECT_NE(st.find("(* 1 AxisXToAssembly on AxisX *)"), std::string::npos) << st;
  const std::string html = virtcom::test::readFile((out / "best-1.html").string());
  EXPECT_NE(html.find("optimised sequence best-1"), std::string::npos);
  EXPECT_NE(html.find("<svg"), std::string::npos);
  EXPECT_TRUE(fs::exists(out / "comparison.txt"));

  // Pasted into a copy of the example's program (MAIN.jobs initialised, sequence 0), the job list
  // runs to the cycle the optimiser reported.
  const fs::path cell = out / "cell";
  fs::copy(fs::path(kModel).parent_path(), cell, fs::copy_options::recursive);
  std::string main = virtcom::test::readFile((cell / "plc/main.st").string());
  const std::string decl = "  jobs : ARRAY[1..kMaxJobs] OF ST_Job;\n";
  ASSERT_NE(main.find(decl), std::string::npos);
  main.replace(main.find(decl), decl.size(), st.substr(st.find("jobs : ARRAY")));
  main.replace(main.find("sequence : INT := 3;"), 20, "sequence : INT := 0;");
  {
    std::FILE* f = std::fopen((cell / "plc/main.st").c_str(), "w");
    std::fputs(main.c_str(), f);
    std::fclose(f);
  }
  std::string run;
  ASSERT_EQ(virtcom::e2e::shell(kExe + " run " + (cell / "cell.yaml").string(), run), 0) << run;
  char expected[64];
  std::snprintf(expected, sizeof expected, "Cycle time    %.3f s", best);
  EXPECT_NE(run.find(expected), std::string::npos) << expected << "\n" << run;
  fs::remove_all(out);
}

TEST(Optimise, SameSeedAndBudgetGiveTheSameResultWithOneOrTwoThreads) {
  std::string one, two;
  const std::string cmd = kExe + " optimise " + kModel + " --method anneal --budget-evals 12 --seed 5 --quiet";
  ASSERT_EQ(virtcom::e2e::shell(cmd + " --jobs 1", one), 0) << one;
  ASSERT_EQ(virtcom::e2e::shell(cmd + " --jobs 2", two), 0) << two;
  auto table = [](const std::string& s) { return s.substr(s.find("| sequence |")); };
  EXPECT_EQ(table(one), table(two));
}

TEST(Optimise, ModelMistakeIsReportedAtItsLocation) {
  const fs::path dir = tempDir("bad");
  const fs::path model = dir / "process.yaml";
  std::string text = virtcom::test::readFile(kModel);
  text.replace(text.find("after: [PickPin1, "), 18, "after: [PickPn1, ");
  text.replace(text.find("cell: cell.yaml"), 15, "cell: " + (fs::path(kModel).parent_path() / "cell.yaml").string());
  {
    std::FILE* f = std::fopen(model.c_str(), "w");
    std::fputs(text.c_str(), f);
    std::fclose(f);
  }
  std::string out;
  EXPECT_EQ(virtcom::e2e::shell(kExe + " optimise " + model.string(), out), 1);
  EXPECT_NE(out.find("process.yaml:31:"), std::string::npos) << out;
  EXPECT_NE(out.find("error[C070]: 'after' of 'PlacePin1' names 'PickPn1', which is no operation of the model"), std::string::npos) << out;
  fs::remove_all(dir);
}

const std::string kSweep = std::string(VIRTCOM_SOURCE_DIR) + "/examples/gearbox-cell/sweep.yaml";

TEST(Sweep, GearboxRowsAsCsvAndShardsMergeIntoTheSameTable) {
  const fs::path out = tempDir("sweep");
  std::string text;
  ASSERT_EQ(virtcom::e2e::shell(kExe + " sweep " + kSweep + " --jobs 2 --csv " + (out / "all.csv").string(), text), 0) << text;
  const std::string all = virtcom::test::readFile((out / "all.csv").string());
  EXPECT_EQ(all.substr(0, all.find('\n')), "point,MAIN.sequence,Robot1.max_speed,cycle_s,energy_J,result");
  EXPECT_NE(all.find("\n4,3,1150 mm/s,70.950,21977.1,ok\n"), std::string::npos) << all;
  EXPECT_EQ(std::count(all.begin(), all.end(), '\n'), 7);
  for (const char* shard : {"1/2", "2/2"}) {
    std::string log;
    const std::string file = (out / ("part" + std::string(1, shard[0]) + ".csv")).string();
    ASSERT_EQ(virtcom::e2e::shell(kExe + " sweep " + kSweep + " --jobs 1 --shard " + shard + " --csv " + file, log), 0) << log;
    EXPECT_NE(log.find("3 of 6 points"), std::string::npos) << log;
  }
  std::string log;
  ASSERT_EQ(virtcom::e2e::shell(kExe + " sweep --merge " + (out / "merged.csv").string() + " " + (out / "part2.csv").string() + " " +
                                    (out / "part1.csv").string(), log), 0) << log;
  EXPECT_EQ(virtcom::test::readFile((out / "merged.csv").string()), all);
  EXPECT_NE(virtcom::e2e::shell(kExe + " sweep --merge " + (out / "twice.csv").string() + " " + (out / "part1.csv").string() + " " +
                                    (out / "part1.csv").string(), log), 0);
  EXPECT_NE(log.find("is in more than one file"), std::string::npos) << log;
  fs::remove_all(out);
}

// The points table of a sweep database, a line per point (the 6 columns of the gearbox sweep).
std::string points(const fs::path& db) {
  virtcom::history::Connection c;
  if (!c.open(db.string(), false)) return "cannot open " + db.string();
  virtcom::history::Statement s(c, "SELECT * FROM points ORDER BY point");
  std::string out;
  while (s.step()) {
    for (int col = 0; col < 6; ++col) out += (s.columnIsNull(col) ? std::string("NULL") : s.columnText(col)) + "|";
    out += "\n";
  }
  return out;
}

TEST(Sweep, SqliteSlicesMergeIntoTheSingleRunsDatabaseAndDrawTheSamePage) {
  const fs::path out = tempDir("sweepdb");
  std::string log;
  ASSERT_EQ(virtcom::e2e::shell(kExe + " sweep " + kSweep + " --jobs 2 --sqlite " + (out / "all.db").string() + " --html " + (out / "all.html").string(), log), 0)
      << log;
  const std::string all = points(out / "all.db");
  EXPECT_NE(all.find("4|3|1150 mm/s|70.95|21977.1"), std::string::npos) << all;
  EXPECT_EQ(std::count(all.begin(), all.end(), '\n'), 6);
  const std::string page = virtcom::test::readFile((out / "all.html").string());
  EXPECT_NE(page.find("<svg"), std::string::npos);
  EXPECT_NE(page.find(">70.950<"), std::string::npos) << "the heat map's cell of sequence 3 at 1150 mm/s";
  for (const char* shard : {"1/2", "2/2"})
    ASSERT_EQ(virtcom::e2e::shell(kExe + " sweep " + kSweep + " --jobs 1 --shard " + shard + " --sqlite " +
                                      (out / ("part" + std::string(1, shard[0]) + ".db")).string(), log), 0) << log;
  ASSERT_EQ(virtcom::e2e::shell(kExe + " sweep --merge " + (out / "merged.db").string() + " " + (out / "part2.db").string() + " " +
                                    (out / "part1.db").string() + " --html " + (out / "merged.html").string(), log), 0) << log;
  EXPECT_EQ(points(out / "merged.db"), all);
  EXPECT_EQ(virtcom::test::readFile((out / "merged.html").string()), page);
  EXPECT_NE(virtcom::e2e::shell(kExe + " sweep --merge " + (out / "twice.db").string() + " " + (out / "part1.db").string() + " " +
                                    (out / "part1.db").string(), log), 0);
  EXPECT_NE(log.find("point 0 is in more than one file"), std::string::npos) << log;
  fs::remove_all(out);
}

#ifdef VIRTCOM_MPIEXEC
// mpirun with N ranks on this machine (as root too, as in CI). Leak checking is off in the ranks:
// Open MPI unloads its plugins at MPI_Finalize, so the allocations they still hold are reported
// from unknown modules that no suppression can name; the same sweeps run in one process, leak
// checked, in the tests above.
std::string mpirun(int ranks) {
  return "ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0 " VIRTCOM_MPIEXEC
         " --oversubscribe --allow-run-as-root -n " + std::to_string(ranks) + " ";
}

TEST(Sweep, MpiRanksWriteTheRowsOfASingleProcess) {
  const fs::path out = tempDir("sweepmpi");
  std::string log;
  ASSERT_EQ(virtcom::e2e::shell(kExe + " sweep " + kSweep + " --jobs 1 --csv " + (out / "one.csv").string(), log), 0) << log;
  ASSERT_EQ(virtcom::e2e::shell(mpirun(2) + kExe + " sweep " + kSweep + " --csv " + (out / "two.csv").string(), log), 0) << log;
  EXPECT_NE(log.find("6 of 6 points (slice 1/1) on 2 MPI ranks"), std::string::npos) << log;
  EXPECT_EQ(virtcom::test::readFile((out / "two.csv").string()), virtcom::test::readFile((out / "one.csv").string()));
  fs::remove_all(out);
}

TEST(Optimise, MpiRanksFindTheResultOfASingleProcess) {
  const fs::path out = tempDir("optmpi");
  const std::string cmd = kExe + " optimise " + kModel + " --method anneal --budget-evals 40 --seed 3 --quiet";
  std::string log;
  ASSERT_EQ(virtcom::e2e::shell(cmd + " --jobs 1 > " + (out / "one.txt").string(), log), 0) << log;
  ASSERT_EQ(virtcom::e2e::shell(mpirun(3) + cmd + " > " + (out / "three.txt").string(), log), 0) << log;
  const std::string one = virtcom::test::readFile((out / "one.txt").string()), three = virtcom::test::readFile((out / "three.txt").string());
  EXPECT_NE(three.find("1 thread(s) on each of 3 MPI ranks"), std::string::npos) << three;
  auto result = [](const std::string& s) { return s.substr(std::min(s.size(), s.find("| sequence |"))); };
  EXPECT_NE(result(one).find("found: best-1"), std::string::npos) << one;
  EXPECT_EQ(result(three), result(one));
  fs::remove_all(out);
}
#endif

TEST(Sweep, SlurmScriptRunsOneSlicePerArrayTask) {
  std::string out;
  ASSERT_EQ(virtcom::e2e::shell(kExe + " sweep " + kSweep + " --slurm-script 4", out), 0) << out;
  EXPECT_NE(out.find("#SBATCH --array=1-4"), std::string::npos) << out;
  EXPECT_NE(out.find("--shard ${SLURM_ARRAY_TASK_ID}/4"), std::string::npos) << out;
  EXPECT_NE(out.find("--csv 'sweep-'${SLURM_ARRAY_TASK_ID}'.csv'"), std::string::npos) << out;
  EXPECT_NE(out.find("virtcom sweep --merge 'sweep.csv' 'sweep-'*'.csv'"), std::string::npos) << out;
  EXPECT_NE(virtcom::e2e::shell(kExe + " sweep " + kSweep + " --slurm-script 4 --html page.html", out), 0);
  EXPECT_NE(out.find("add --sqlite FILE"), std::string::npos) << out;
}

// The script as Slurm runs it: each array task in the submit directory with its
// SLURM_ARRAY_TASK_ID, then the merge its comment gives; the result is the single run's database
// and page.
TEST(Sweep, SlurmScriptTasksAndItsMergeGiveTheSingleRunsDatabase) {
  const fs::path out = tempDir("slurm");
  const fs::path single = out / "single", cluster = out / "my results";
  fs::create_directories(single);
  fs::create_directories(cluster);
  std::string log;
  ASSERT_EQ(virtcom::e2e::shell(kExe + " sweep " + kSweep + " --sqlite " + (single / "all.db").string() + " --html " +
                                    (single / "all.html").string(), log), 0) << log;
  const std::string inCluster = "cd '" + cluster.string() + "' && PATH='" + fs::path(kExe).parent_path().string() + "':$PATH ";
  ASSERT_EQ(virtcom::e2e::shell(inCluster + "virtcom sweep " + kSweep + " --slurm-script 3 --sqlite all.db --html all.html > sweep.sbatch", log), 0) << log;
  for (int task = 1; task <= 3; ++task)
    ASSERT_EQ(virtcom::e2e::shell(inCluster + "SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " bash sweep.sbatch", log), 0) << log;
  const std::string script = virtcom::test::readFile((cluster / "sweep.sbatch").string());
  const size_t merge = script.find("virtcom sweep --merge");
  ASSERT_NE(merge, std::string::npos) << script;
  ASSERT_EQ(virtcom::e2e::shell(inCluster + script.substr(merge, script.find('\n', merge) - merge), log), 0) << log;
  EXPECT_EQ(points(cluster / "all.db"), points(single / "all.db"));
  EXPECT_EQ(virtcom::test::readFile((cluster / "all.html").string()), virtcom::test::readFile((single / "all.html").string()));
  fs::remove_all(out);
}

TEST(Optimise, HelpNamesEveryOption) {
  std::string out;
  ASSERT_EQ(virtcom::e2e::shell(kExe + " optimise --help", out), 0);
  for (const char* option : {"--objective", "--budget-evals", "--budget-time", "--seed", "--jobs", "--method", "--out", "--quiet", "--batch"})
    EXPECT_NE(out.find(option), std::string::npos) << option;
  ASSERT_EQ(virtcom::e2e::shell(kExe + " sweep --help", out), 0);
  for (const char* option : {"--csv", "--shard", "--merge", "--slurm-script", "--jobs", "--sqlite", "--html"}) EXPECT_NE(out.find(option), std::string::npos) << option;
}

}  // namespace
