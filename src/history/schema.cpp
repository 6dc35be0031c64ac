#include "history/schema.hpp"

#include <filesystem>

namespace virtcom::history {

namespace {

// kMigrations[v] takes a database from user_version v to v + 1; index 0 creates schema 1 in an
// empty file. A new schema version appends a step here (never edits a released one) and bumps
// kSchemaVersion. Times are virtual ns since the start of the run; `raw` values are the tag
// bus's 64-bit representation (core/tag_bus.hpp) stored as INTEGER.
constexpr const char* kMigrations[] = {
    R"sql(
CREATE TABLE runs (
  id INTEGER PRIMARY KEY AUTOINCREMENT,  -- never reused, even after retention deleted the newest
  cell_name TEXT NOT NULL,
  cell_file TEXT NOT NULL,
  timeline TEXT NOT NULL,
  wall_start_ns INTEGER NOT NULL,
  end_ns INTEGER NOT NULL DEFAULT 0,
  end_reason TEXT,
  end_message TEXT NOT NULL DEFAULT '',
  cycles_completed INTEGER NOT NULL DEFAULT 0,
  cycle_start_ns INTEGER NOT NULL DEFAULT 0,
  cycle_end_ns INTEGER NOT NULL DEFAULT 0,
  drops INTEGER NOT NULL DEFAULT 0,
  writer_error TEXT NOT NULL DEFAULT ''
) STRICT;
CREATE TABLE signals (
  run INTEGER NOT NULL, id INTEGER NOT NULL, name TEXT NOT NULL, type TEXT NOT NULL, initial INTEGER NOT NULL,
  PRIMARY KEY (run, id)
) STRICT, WITHOUT ROWID;
CREATE TABLE changes (
  run INTEGER NOT NULL, t_ns INTEGER NOT NULL, signal INTEGER NOT NULL, raw INTEGER NOT NULL,
  PRIMARY KEY (run, t_ns, signal)
) STRICT, WITHOUT ROWID;
CREATE TABLE labels (
  run INTEGER NOT NULL, id INTEGER NOT NULL, text TEXT NOT NULL,
  PRIMARY KEY (run, id)
) STRICT, WITHOUT ROWID;
CREATE TABLE devices (
  run INTEGER NOT NULL, id INTEGER NOT NULL, name TEXT NOT NULL, type TEXT NOT NULL, lane_group TEXT NOT NULL,
  busy_ns INTEGER NOT NULL DEFAULT 0, energy_j REAL NOT NULL DEFAULT 0,
  PRIMARY KEY (run, id)
) STRICT, WITHOUT ROWID;
CREATE TABLE activities (
  run INTEGER NOT NULL, id INTEGER NOT NULL, device INTEGER NOT NULL, label INTEGER NOT NULL,
  start_ns INTEGER NOT NULL, end_ns INTEGER, energy_j REAL NOT NULL, error_code INTEGER NOT NULL,
  PRIMARY KEY (run, id)
) STRICT, WITHOUT ROWID;
CREATE INDEX activities_by_start ON activities (run, start_ns);
CREATE TABLE faults (
  run INTEGER NOT NULL, id INTEGER NOT NULL, t_ns INTEGER NOT NULL, source TEXT NOT NULL, message TEXT NOT NULL,
  PRIMARY KEY (run, id)
) STRICT, WITHOUT ROWID;
CREATE TABLE collisions (
  run INTEGER NOT NULL, id INTEGER NOT NULL, t_ns INTEGER NOT NULL, zone INTEGER NOT NULL,
  device_a INTEGER NOT NULL, device_b INTEGER NOT NULL, activity_a INTEGER NOT NULL, activity_b INTEGER NOT NULL,
  PRIMARY KEY (run, id)
) STRICT, WITHOUT ROWID;
CREATE TABLE cycles (
  run INTEGER NOT NULL, number INTEGER NOT NULL, start_ns INTEGER NOT NULL, end_ns INTEGER NOT NULL,
  PRIMARY KEY (run, number)
) STRICT, WITHOUT ROWID;
)sql",
    // 2: the production a monitored plant made per planned shift (virtcom monitor with a `plan:`).
    R"sql(
CREATE TABLE production (
  run INTEGER NOT NULL, start_wall_ns INTEGER NOT NULL, end_wall_ns INTEGER NOT NULL, watched_from_wall_ns INTEGER NOT NULL,
  day TEXT NOT NULL, shift TEXT NOT NULL, plan INTEGER NOT NULL, plan_now REAL NOT NULL, actual INTEGER NOT NULL,
  PRIMARY KEY (run, start_wall_ns)
) STRICT, WITHOUT ROWID;
)sql",
    // 3: the audited writes from outside (docs/security.md): ADS, Modbus, OPC UA and HMI clients.
    R"sql(
CREATE TABLE writes (
  run INTEGER NOT NULL, id INTEGER NOT NULL, t_ns INTEGER NOT NULL, wall_ns INTEGER NOT NULL,
  protocol TEXT NOT NULL, peer TEXT NOT NULL, netid TEXT NOT NULL, variable TEXT NOT NULL, location TEXT NOT NULL,
  old_value TEXT NOT NULL, new_value TEXT NOT NULL, forced INTEGER NOT NULL,
  PRIMARY KEY (run, id)
) STRICT, WITHOUT ROWID;
)sql",
};
static_assert(std::size(kMigrations) == kSchemaVersion);

std::string fileError(const std::string& path, const std::string& what) { return path + ": " + what; }

// The file's schema brought to kSchemaVersion, or why not.
std::expected<void, std::string> migrate(Connection& db, const std::string& path, OpenMode mode) {
  int64_t appId = 0, version = 0;
  if (!db.queryInt("PRAGMA application_id", appId) || !db.queryInt("PRAGMA user_version", version))
    return std::unexpected(fileError(path, "not a SQLite database (" + db.errorText() + ")"));
  int64_t objects = 0;
  if (!db.queryInt("SELECT COUNT(*) FROM sqlite_schema", objects)) return std::unexpected(fileError(path, db.errorText()));
  const bool empty = appId == 0 && version == 0 && objects == 0;
  if (empty && mode == OpenMode::Read) return std::unexpected(fileError(path, "an empty SQLite database, not a virtcom history (nothing recorded)"));
  if (!empty && appId != kApplicationId)
    return std::unexpected(fileError(path, "a SQLite database of another application, not a virtcom history (application_id " +
                                               std::to_string(appId) + ", expected " + std::to_string(kApplicationId) + ")"));
  if (version > kSchemaVersion)
    return std::unexpected(fileError(path, "history schema " + std::to_string(version) + " is newer than this virtcom reads (" +
                                               std::to_string(kSchemaVersion) + "): use a newer virtcom"));
  if (version == kSchemaVersion) return {};
  // Incremental auto-vacuum lets retention give pruned pages back to the file system; it must be
  // set before the first table exists.
  if (empty && !db.exec("PRAGMA auto_vacuum = INCREMENTAL")) return std::unexpected(fileError(path, db.errorText()));
  if (!db.exec("BEGIN IMMEDIATE")) return std::unexpected(fileError(path, db.errorText()));
  for (int64_t v = version; v < kSchemaVersion; ++v)
    if (!db.exec(kMigrations[v])) {
      std::string why = db.errorText();
      db.exec("ROLLBACK");
      return std::unexpected(fileError(path, "cannot create the history schema: " + why));
    }
  std::string pragmas = "PRAGMA application_id = " + std::to_string(kApplicationId) + "; PRAGMA user_version = " + std::to_string(kSchemaVersion);
  if (!db.exec(pragmas.c_str()) || !db.exec("COMMIT")) {
    std::string why = db.errorText();
    db.exec("ROLLBACK");
    return std::unexpected(fileError(path, why));
  }
  return {};
}

std::expected<void, std::string> quickCheck(Connection& db, const std::string& path) {
  Statement check(db, "PRAGMA quick_check");
  std::string problems;
  while (check.step()) {
    std::string line = check.columnText(0);
    if (line == "ok") return {};
    problems += (problems.empty() ? "" : "; ") + line;
  }
  if (problems.empty()) problems = db.errorText();
  return std::unexpected(fileError(path, "the integrity check failed (" + problems + "): the file is damaged"));
}

}  // namespace

std::expected<Connection, std::string> openDatabase(const std::string& path, OpenMode mode) {
  std::error_code ec;
  if (mode == OpenMode::Read && !std::filesystem::is_regular_file(path, ec))
    return std::unexpected(fileError(path, std::filesystem::exists(path, ec) ? "not a file" : "no such file"));
  Connection db;
  if (!db.open(path, mode == OpenMode::Record)) return std::unexpected(fileError(path, "cannot open (" + db.errorText() + ")"));
  // The journal mode first: it is the first read of the file, so a non-SQLite file fails here.
  int64_t ignored = 0;
  if (!db.queryInt("PRAGMA journal_mode = WAL", ignored))
    return std::unexpected(fileError(path, "not a SQLite database (" + db.errorText() + ")"));
  if (!db.exec("PRAGMA synchronous = NORMAL")) return std::unexpected(fileError(path, db.errorText()));
  auto migrated = migrate(db, path, mode);
  if (!migrated) return std::unexpected(migrated.error());
  auto checked = quickCheck(db, path);
  if (!checked) return std::unexpected(checked.error());
  return db;
}

}  // namespace virtcom::history
