// Sweep databases: the tables a slice writes (one column per parameter and KPI), read back as
// written, slices merged into the database of a single run, and the merges refused.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "history/sqlite.hpp"
#include "optimize/sweep_db.hpp"

namespace virtcom::optimize {
namespace {

namespace fs = std::filesystem;

struct SweepDb : testing::Test {
  fs::path dir = fs::temp_directory_path() / ("virtcom_sweep_db_" + std::to_string(::getpid()));
  SweepSpec spec;
  std::vector<SweepRow> rows;

  void SetUp() override {
    fs::remove_all(dir);
    fs::create_directories(dir);
    spec.file = "/somewhere/sweep.yaml";
    spec.cellFile = "/somewhere/cell.yaml";
    spec.parameters = {{"MAIN.sequence", {"2", "3"}, {}}, {"Robot1.max_speed", {"900 mm/s", "1150 mm/s"}, {}}};
    for (size_t p = 0; p < 4; ++p) {
      SweepRow r{p, {spec.parameters[0].values[p / 2], spec.parameters[1].values[p % 2]}, {}};
      r.eval.feasible = p != 3;
      r.eval.cycleNs = 70'000'000'000 + static_cast<int64_t>(p) * 1'234'567;
      r.eval.energyJ = 21977.125 + static_cast<double>(p) / 3;
      if (p == 3) r.eval.reason = "collision at 33.28 s: Robot1, Robot2 in SharedTable";
      rows.push_back(r);
    }
  }
  void TearDown() override { fs::remove_all(dir); }
  std::string path(const char* name) const { return (dir / name).string(); }

  // Slice I of N as --shard writes it.
  std::string slice(size_t index, size_t count, const char* name) {
    std::vector<SweepRow> mine;
    for (size_t p = index - 1; p < rows.size(); p += count) mine.push_back(rows[p]);
    EXPECT_EQ(writeSweepDb(path(name), spec, {index, count, rows.size()}, mine), "");
    return path(name);
  }
};

// Every row of a query (of `columns` columns) as text, tab-separated, one line each.
std::string dump(const std::string& file, const char* sql, int columns) {
  history::Connection db;
  EXPECT_TRUE(db.open(file, false));
  history::Statement s(db, sql);
  std::string out;
  while (s.step()) {
    for (int c = 0; c < columns; ++c) out += (s.columnIsNull(c) ? std::string("NULL") : s.columnText(c)) + "\t";
    out += "\n";
  }
  return out;
}

TEST_F(SweepDb, PointsHaveAColumnPerParameterAndKpiAndTheSweepIsDescribed) {
  EXPECT_EQ(writeSweepDb(path("all.db"), spec, {1, 1, 4}, rows), "");
  EXPECT_TRUE(isSqliteFile(path("all.db")));
  const std::string points =
      dump(path("all.db"), "SELECT point, \"MAIN.sequence\", \"Robot1.max_speed\", round(cycle_s, 3), energy_J, result FROM points", 6);
  EXPECT_NE(points.find("1\t2\t1150 mm/s\t70.001\t"), std::string::npos) << points;
  EXPECT_NE(points.find("3\t3\t1150 mm/s\tNULL\tNULL\tcollision at 33.28 s: Robot1, Robot2 in SharedTable\t"), std::string::npos) << points;
  const std::string sweep = dump(path("all.db"), "SELECT key, value FROM sweep ORDER BY key", 2);
  EXPECT_NE(sweep.find("file\tsweep.yaml\t"), std::string::npos) << sweep;
  EXPECT_NE(sweep.find("parameters\tMAIN.sequence\nRobot1.max_speed\t"), std::string::npos) << sweep;
  EXPECT_NE(sweep.find("points\t4\t"), std::string::npos) << sweep;
  EXPECT_EQ(dump(path("all.db"), "SELECT slice, slices, points FROM slices", 3), "1\t1\t4\t\n");

  report::SweepTable back;
  ASSERT_EQ(readSweepDb(path("all.db"), back), "");
  EXPECT_EQ(back.parameters, (std::vector<std::string>{"MAIN.sequence", "Robot1.max_speed"}));
  ASSERT_EQ(back.rows.size(), 4u);
  EXPECT_EQ(back.rows[1].cycleS, static_cast<double>(rows[1].eval.cycleNs) * 1e-9) << "exact, not rounded as in the CSV";
  EXPECT_FALSE(back.rows[3].feasible);
  EXPECT_EQ(back.rows[3].result, rows[3].eval.reason);
}

TEST_F(SweepDb, SlicesMergeIntoTheDatabaseOfASingleRun) {
  ASSERT_EQ(writeSweepDb(path("all.db"), spec, {1, 1, 4}, rows), "");
  const std::string a = slice(1, 2, "a.db"), b = slice(2, 2, "b.db");
  ASSERT_EQ(mergeSweepDbs(path("merged.db"), {b, a}), "");
  const char* points = "SELECT * FROM points ORDER BY point";
  EXPECT_EQ(dump(path("merged.db"), points, 6), dump(path("all.db"), points, 6));
  const char* sweep = "SELECT key, value FROM sweep ORDER BY key";
  EXPECT_EQ(dump(path("merged.db"), sweep, 2), dump(path("all.db"), sweep, 2));
  EXPECT_EQ(dump(path("merged.db"), "SELECT slice, slices, points FROM slices", 3), "1\t2\t2\t\n2\t2\t2\t\n");
}

TEST_F(SweepDb, MergeRefusesAPointTwiceAnotherSweepAndAFileThatIsNoDatabase) {
  const std::string a = slice(1, 2, "a.db");
  EXPECT_EQ(mergeSweepDbs(path("twice.db"), {a, a}), "point 0 is in more than one file");
  spec.seed = 9;
  const std::string other = slice(2, 2, "other.db");
  EXPECT_NE(mergeSweepDbs(path("mixed.db"), {a, other}).find("holds another sweep than"), std::string::npos);
  std::ofstream(path("rows.csv")) << "point,a\n0,1\n";
  EXPECT_EQ(mergeSweepDbs(path("csv.db"), {a, path("rows.csv")}), "cannot read '" + path("rows.csv") + "' as a SQLite database");
  EXPECT_FALSE(isSqliteFile(path("rows.csv")));
}

}  // namespace
}  // namespace virtcom::optimize
