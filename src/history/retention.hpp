#pragma once
// How long a history keeps its runs: the oldest runs are deleted when they are older than a
// number of days or while the file is larger than a size. The run being recorded is never
// deleted, so one run longer than the limits keeps growing.
#include <cstdint>

#include "history/sqlite.hpp"

namespace virtcom::history {

struct Retention {
  int64_t keepDays = 0;   // 0: no age limit
  int64_t maxBytes = 0;   // 0: no size limit
  bool any() const { return keepDays > 0 || maxBytes > 0; }
};

// Deletes the runs (and all their rows) beyond `limits`, oldest first, never `currentRun`, and
// gives the freed pages back to the file system. `nowUtcNs`: the wall-clock time runs are aged
// against. The number of runs deleted, or -1 on a database error (see db.errorText()). Blocks on
// I/O for as long as deleting takes.
int64_t pruneRuns(Connection& db, const Retention& limits, int64_t currentRun, int64_t nowUtcNs);

// Bytes of the file in use (pages minus free pages).
int64_t usedBytes(Connection& db);

}  // namespace virtcom::history
