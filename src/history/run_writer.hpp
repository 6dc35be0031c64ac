#pragma once
// The SQLite side of recording one run: the run's row and its tables (docs/history.md), written
// with prepared statements in one transaction per call. Used by the recorder: writeStart and
// writeEnd on the simulation thread (before the writer thread starts, after it stopped),
// writeBatch on the writer thread.
#include <cstdint>
#include <string>
#include <vector>

#include "core/trace.hpp"
#include "history/event_queue.hpp"
#include "history/sqlite.hpp"

namespace virtcom::history {

struct RunIdentity {
  std::string cellName;
  std::string cellFile;
  int64_t wallStartNs = 0;  // UTC ns since 1970
  std::vector<std::string> timeline;  // the report's timeline signals, in order
  std::vector<std::string> shiftNames;  // a monitored plant's planned shifts, by index (Production events)
};

// One planned shift as a monitored plant worked it (`virtcom monitor` with a `plan:`; the
// `production` table of docs/history.md). Wall times are local, ns since 1970-01-01 00:00.
struct ProductionRow {
  std::string day;    // "2026-12-02"
  std::string shift;  // its name in the plan
  int64_t startWallNs = 0, endWallNs = 0, watchedFromWallNs = 0;
  int64_t plan = 0;   // the whole shift's planned parts
  double planNow = 0; // pro-rated to the part watched
  int64_t actual = 0; // parts (cycles) completed
};

class RunWriter {
 public:
  explicit RunWriter(Connection& db);

  // Inserts the run's row, its signals with their initial values, devices and labels. The new
  // run's id, or -1 (see error()).
  int64_t writeStart(const Trace& trace, const RunIdentity& identity);
  // The first `count` events of `queue` (whole faults: a fault's text events follow it), and the
  // run's progress (virtual time recorded up to, drops so far). False on a database error.
  bool writeBatch(const EventQueue& queue, size_t count, int64_t progressNs, uint64_t drops);
  // How the run ended, the labels interned during the run, the devices' totals.
  bool writeEnd(const Trace& trace, uint64_t drops, const std::string& writerError);
  // The run's shifts, replacing what was written for them before.
  bool writeProduction(const std::vector<ProductionRow>& rows);

  const std::string& error() const { return error_; }
  Connection& connection() { return db_; }

 private:
  bool fail();
  bool writeEvent(const EventQueue& queue, size_t& i);
  bool writeLabels(const Trace& trace);
  // The `bytes` of text in the text events after event i (advancing i past them), in text_.
  std::string_view readTexts(const EventQueue& queue, size_t& i, size_t bytes);
  void writeFault(const EventQueue& queue, size_t& i);
  void writeExternalWrite(const EventQueue& queue, size_t& i);

  Connection& db_;
  int64_t run_ = -1;
  Statement change_, activity_, collision_, fault_, cycle_, progress_, label_, production_, write_;
  std::vector<std::string> shiftNames_;
  std::string error_;
  std::string text_;  // reused: the texts of the fault or write being reassembled
};

}  // namespace virtcom::history
