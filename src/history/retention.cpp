#include "history/retention.hpp"

#include <cstdint>

namespace virtcom::history {

namespace {

// Every table keyed by run, in the order a run is deleted (the runs row last).
constexpr const char* kDeleteRun[] = {
    "DELETE FROM changes WHERE run = ?1",  "DELETE FROM activities WHERE run = ?1", "DELETE FROM faults WHERE run = ?1",
    "DELETE FROM collisions WHERE run = ?1", "DELETE FROM cycles WHERE run = ?1",   "DELETE FROM production WHERE run = ?1",
    "DELETE FROM writes WHERE run = ?1",   "DELETE FROM labels WHERE run = ?1",
    "DELETE FROM devices WHERE run = ?1",  "DELETE FROM signals WHERE run = ?1",    "DELETE FROM runs WHERE id = ?1",
};

bool deleteRun(Connection& db, int64_t run) {
  if (!db.exec("BEGIN")) return false;
  for (const char* sql : kDeleteRun) {
    Statement s(db, sql);
    if (!s.bind(1, run).run()) {
      db.exec("ROLLBACK");
      return false;
    }
  }
  return db.exec("COMMIT");
}

// The oldest run other than `currentRun` started before `beforeUtcNs`, or 0.
int64_t oldestRun(Connection& db, int64_t currentRun, int64_t beforeUtcNs) {
  Statement s(db, "SELECT id FROM runs WHERE id != ?1 AND wall_start_ns < ?2 ORDER BY id LIMIT 1");
  s.bind(1, currentRun).bind(2, beforeUtcNs);
  return s.step() ? s.columnInt(0) : 0;
}

}  // namespace

int64_t usedBytes(Connection& db) {
  int64_t pages = 0, freePages = 0, pageSize = 0;
  db.queryInt("PRAGMA page_count", pages);
  db.queryInt("PRAGMA freelist_count", freePages);
  db.queryInt("PRAGMA page_size", pageSize);
  return (pages - freePages) * pageSize;
}

int64_t pruneRuns(Connection& db, const Retention& limits, int64_t currentRun, int64_t nowUtcNs) {
  int64_t deleted = 0;
  if (limits.keepDays > 0) {
    const int64_t oldestKept = nowUtcNs - limits.keepDays * 86'400'000'000'000;
    while (int64_t run = oldestRun(db, currentRun, oldestKept)) {
      if (!deleteRun(db, run)) return -1;
      ++deleted;
    }
  }
  if (limits.maxBytes > 0) {
    while (usedBytes(db) > limits.maxBytes) {
      int64_t run = oldestRun(db, currentRun, INT64_MAX);
      if (run == 0) break;
      if (!deleteRun(db, run)) return -1;
      ++deleted;
    }
  }
  if (deleted > 0 && !db.exec("PRAGMA incremental_vacuum")) return -1;
  return deleted;
}

}  // namespace virtcom::history
