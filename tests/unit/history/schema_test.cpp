// Opening files as history databases: created when new, refused with a clear message when they
// are something else.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "history/schema.hpp"
#include "history_fixture.hpp"

namespace virtcom::history {
namespace {

using test::HistoryTest;
using ::testing::HasSubstr;

class Schema : public HistoryTest {};

TEST_F(Schema, RecordCreatesTheSchemaInWalModeAndReadOpensIt) {
  ASSERT_TRUE(openDatabase(path("h.sqlite"), OpenMode::Record).has_value());
  auto db = openDatabase(path("h.sqlite"), OpenMode::Read);
  ASSERT_TRUE(db.has_value()) << db.error();
  int64_t version = 0, appId = 0, tables = 0;
  ASSERT_TRUE(db->queryInt("PRAGMA user_version", version));
  ASSERT_TRUE(db->queryInt("PRAGMA application_id", appId));
  ASSERT_TRUE(db->queryInt("SELECT COUNT(*) FROM sqlite_schema WHERE type = 'table' AND name NOT LIKE 'sqlite_%'", tables));
  EXPECT_EQ(version, kSchemaVersion);
  EXPECT_EQ(appId, kApplicationId);
  EXPECT_EQ(tables, 11);  // schema 3 added `writes`
  Statement mode(*db, "PRAGMA journal_mode");
  ASSERT_TRUE(mode.step());
  EXPECT_EQ(mode.columnText(0), "wal");
}

TEST_F(Schema, TimeRangeQueriesUseTheIndexes) {
  auto db = openDatabase(path("h.sqlite"), OpenMode::Record);
  ASSERT_TRUE(db.has_value());
  auto plan = [&](const char* sql) {
    Statement s(*db, (std::string("EXPLAIN QUERY PLAN ") + sql).c_str());
    std::string text;
    while (s.step()) text += s.columnText(3) + "\n";
    return text;
  };
  EXPECT_THAT(plan("SELECT * FROM changes WHERE run = 1 AND t_ns BETWEEN 5 AND 9"), HasSubstr("USING PRIMARY KEY (run=? AND t_ns>? AND t_ns<?)"));
  EXPECT_THAT(plan("SELECT * FROM activities WHERE run = 1 AND start_ns <= 9"), HasSubstr("USING INDEX activities_by_start (run=? AND start_ns<?)"));
}

TEST_F(Schema, MissingFileIsRefusedForReading) {
  auto db = openDatabase(path("none.sqlite"), OpenMode::Read);
  ASSERT_FALSE(db.has_value());
  EXPECT_EQ(db.error(), path("none.sqlite") + ": no such file");
  EXPECT_FALSE(std::filesystem::exists(path("none.sqlite")));
}

TEST_F(Schema, TextFileIsNotSqlite) {
  std::ofstream(path("notes.sqlite")) << "these are not the pages you are looking for\n";
  for (OpenMode mode : {OpenMode::Read, OpenMode::Record}) {
    auto db = openDatabase(path("notes.sqlite"), mode);
    ASSERT_FALSE(db.has_value());
    EXPECT_THAT(db.error(), HasSubstr("notes.sqlite: not a SQLite database (file is not a database)"));
  }
}

TEST_F(Schema, OtherApplicationsSqliteIsRefused) {
  {
    Connection other;
    ASSERT_TRUE(other.open(path("other.sqlite"), true));
    ASSERT_TRUE(other.exec("CREATE TABLE parts (id INTEGER)"));
  }
  for (OpenMode mode : {OpenMode::Read, OpenMode::Record}) {
    auto db = openDatabase(path("other.sqlite"), mode);
    ASSERT_FALSE(db.has_value());
    EXPECT_THAT(db.error(), HasSubstr("a SQLite database of another application, not a virtcom history"));
  }
}

TEST_F(Schema, NewerSchemaIsRefused) {
  {
    auto db = openDatabase(path("h.sqlite"), OpenMode::Record);
    ASSERT_TRUE(db.has_value());
    ASSERT_TRUE(db->exec("PRAGMA user_version = 99"));
  }
  auto db = openDatabase(path("h.sqlite"), OpenMode::Read);
  ASSERT_FALSE(db.has_value());
  EXPECT_THAT(db.error(), HasSubstr("history schema 99 is newer than this virtcom reads (" + std::to_string(kSchemaVersion) + ")"));
}

// A schema-1 file (before the `production` table) is migrated when opened, its runs kept.
TEST_F(Schema, Version1FileIsMigratedKeepingItsRuns) {
  {
    auto db = openDatabase(path("h.sqlite"), OpenMode::Record);
    ASSERT_TRUE(db.has_value());
    ASSERT_TRUE(db->exec("DROP TABLE production; DROP TABLE writes; PRAGMA user_version = 1"));
    ASSERT_TRUE(db->exec("INSERT INTO runs (cell_name, cell_file, timeline, wall_start_ns) VALUES ('old', '/c.yaml', '', 0)"));
  }
  auto db = openDatabase(path("h.sqlite"), OpenMode::Read);
  ASSERT_TRUE(db.has_value()) << db.error();
  int64_t version = 0, production = 0, writes = 0, runs = 0;
  ASSERT_TRUE(db->queryInt("PRAGMA user_version", version));
  ASSERT_TRUE(db->queryInt("SELECT COUNT(*) FROM sqlite_schema WHERE name = 'production'", production));
  ASSERT_TRUE(db->queryInt("SELECT COUNT(*) FROM sqlite_schema WHERE name = 'writes'", writes));
  ASSERT_TRUE(db->queryInt("SELECT COUNT(*) FROM runs WHERE cell_name = 'old'", runs));
  EXPECT_EQ(version, kSchemaVersion);
  EXPECT_EQ(production, 1);
  EXPECT_EQ(writes, 1) << "schema 3: the audited writes";
  EXPECT_EQ(runs, 1);
}

TEST_F(Schema, EmptySqliteFileIsNotAHistoryForReading) {
  { std::ofstream empty(path("empty.sqlite")); }
  auto db = openDatabase(path("empty.sqlite"), OpenMode::Read);
  ASSERT_FALSE(db.has_value());
  EXPECT_THAT(db.error(), HasSubstr("an empty SQLite database, not a virtcom history"));
}

TEST_F(Schema, DamagedFileFailsTheIntegrityCheck) {
  int64_t root = 0, pageSize = 0;
  {
    auto db = openDatabase(path("h.sqlite"), OpenMode::Record);
    ASSERT_TRUE(db.has_value());
    ASSERT_TRUE(db->exec("PRAGMA journal_mode = DELETE"));  // everything in the main file
    ASSERT_TRUE(db->exec("BEGIN"));
    for (int i = 0; i < 2000; ++i)
      ASSERT_TRUE(db->exec(("INSERT INTO changes VALUES (1, " + std::to_string(i) + ", 0, 0)").c_str()));
    ASSERT_TRUE(db->exec("COMMIT"));
    ASSERT_TRUE(db->queryInt("SELECT rootpage FROM sqlite_schema WHERE name = 'changes'", root));
    ASSERT_TRUE(db->queryInt("PRAGMA page_size", pageSize));
  }
  {
    // Garbage over the page header and cell pointers of the changes table's root page.
    std::fstream f(path("h.sqlite"), std::ios::in | std::ios::out | std::ios::binary);
    f.seekp((root - 1) * pageSize);
    const std::string garbage(64, '\x5a');
    f.write(garbage.data(), static_cast<std::streamsize>(garbage.size()));
  }
  auto db = openDatabase(path("h.sqlite"), OpenMode::Read);
  ASSERT_FALSE(db.has_value());
  EXPECT_THAT(db.error(), HasSubstr("h.sqlite: the integrity check failed ("));
  EXPECT_THAT(db.error(), HasSubstr("): the file is damaged"));
}

}  // namespace
}  // namespace virtcom::history
