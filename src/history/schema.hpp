#pragma once
// The history database's schema (documented table by table in docs/history.md) and opening a
// file as a history database: created when new, checked when not.
#include <cstdint>
#include <expected>
#include <string>

#include "history/sqlite.hpp"

namespace virtcom::history {

// PRAGMA application_id of every history database ("VCHI"): tells a history file from any other
// SQLite file.
inline constexpr int64_t kApplicationId = 0x56434849;
// PRAGMA user_version: the schema version this build reads and writes. A newer file is refused;
// older files are migrated step by step (kMigrations in schema.cpp).
inline constexpr int64_t kSchemaVersion = 3;

enum class OpenMode {
  Record,  // creates the file and the schema if missing (virtcom run/serve --history)
  Read,    // the file must exist and be a history database (virtcom history)
};

// Opens `path` as a history database in WAL mode (synchronous=NORMAL: a commit survives the
// process being killed), after PRAGMA quick_check. The error names the file and says what is
// wrong: missing, not SQLite, another application's SQLite file, a newer schema, or damaged.
// Blocks on I/O; quick_check reads the whole file.
std::expected<Connection, std::string> openDatabase(const std::string& path, OpenMode mode);

}  // namespace virtcom::history
