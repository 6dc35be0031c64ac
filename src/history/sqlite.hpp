#pragma once
// Thin RAII handles over the SQLite C API (Debian libsqlite3-dev): a connection and a prepared
// statement. The historian's, and the one SQLite wrapper of the project (optimize's sweep
// databases use it too). They never throw; a failing call returns false and the
// connection keeps SQLite's message (errorText()).
#include <cstdint>
#include <string>
#include <string_view>

struct sqlite3;
struct sqlite3_stmt;

namespace virtcom::history {

class Connection {
 public:
  Connection() = default;
  ~Connection();
  Connection(Connection&& other) noexcept : db_(other.db_) { other.db_ = nullptr; }
  Connection& operator=(Connection&& other) noexcept;
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  // Opens `path` read-write; `create`: creates a missing file, otherwise a missing file fails.
  bool open(const std::string& path, bool create);
  bool isOpen() const { return db_ != nullptr; }
  // Runs one or more statements that return no rows (DDL, PRAGMA x = y, BEGIN, COMMIT).
  bool exec(const char* sql);
  // The first column of the first row of `sql` as an integer (PRAGMA user_version, COUNT(*)).
  bool queryInt(const char* sql, int64_t& value);
  // SQLite's message for the last failed call.
  std::string errorText() const;
  int64_t lastInsertRowid() const;
  sqlite3* handle() const { return db_; }

 private:
  sqlite3* db_ = nullptr;
};

// A prepared statement: bind parameters (1-based), step through rows, read columns (0-based),
// reset to run again. Binding and stepping do not allocate beyond SQLite's own page cache.
class Statement {
 public:
  Statement() = default;
  Statement(Connection& db, const char* sql);
  ~Statement();
  Statement(Statement&& other) noexcept : stmt_(other.stmt_) { other.stmt_ = nullptr; }
  Statement& operator=(Statement&& other) noexcept;
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  bool valid() const { return stmt_ != nullptr; }
  Statement& bind(int index, int64_t value);
  Statement& bind(int index, double value);
  Statement& bind(int index, std::string_view text);
  Statement& bindNull(int index);
  // True while there is a row; false when done or on an error (then done() is false).
  bool step();
  // One step of a statement that returns no rows, then reset; false on an error.
  bool run();
  void reset();
  bool done() const { return done_; }

  int64_t columnInt(int column) const;
  double columnDouble(int column) const;
  std::string columnText(int column) const;
  bool columnIsNull(int column) const;

 private:
  sqlite3_stmt* stmt_ = nullptr;
  bool done_ = false;
};

}  // namespace virtcom::history
