#pragma once
// Reading a history database (docs/history.md): its runs, and a run's signal changes and
// activities in a virtual-time range, streamed or as a core::Trace that every report writer of
// src/report takes. `virtcom history` and the HMI read history through this.
#include <cstdint>
#include <expected>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/trace.hpp"
#include "history/run_writer.hpp"
#include "history/sqlite.hpp"

namespace virtcom::history {

struct RunSummary {
  int64_t id = 0;
  std::string cellName;
  std::string cellFile;
  std::vector<std::string> timeline;  // the report's timeline signals when recorded
  int64_t wallStartNs = 0;   // UTC ns since 1970
  int64_t endNs = 0;         // virtual time recorded up to (the end, once the run ended)
  bool ended = false;        // false: the process stopped without ending the run (killed)
  std::string endReason;     // runEndName() text when ended
  std::string endMessage;
  int64_t cyclesCompleted = 0;   // and the measured (last) cycle, as Trace has them
  int64_t cycleStartNs = 0;
  int64_t cycleEndNs = 0;
  int64_t changes = 0;
  int64_t activities = 0;
  int64_t drops = 0;         // events the recorder's full queue refused
  int64_t writes = 0;        // audited writes from outside (the table `writes`, docs/security.md)
  std::string writerError;   // the database error that stopped recording, if any
};

// A closed virtual-time interval [fromNs, toNs]; the default is the whole run.
struct TimeRange {
  int64_t fromNs = 0;
  int64_t toNs = INT64_MAX;
  bool whole() const { return fromNs == 0 && toNs == INT64_MAX; }
};

// One signal of a plot over a time range (HistoryReader::series).
struct Series {
  TagId signal = 0;
  uint64_t before = 0;               // its value just before the range (the initial one if none)
  std::vector<SignalChange> points;  // its changes in the range, or their decimation, in time order
  size_t changes = 0;                // its changes in the range before decimation
  bool decimated() const { return points.size() < changes; }
};

class HistoryReader {
 public:
  // Opens an existing history for reading (see openDatabase: the error says what is wrong).
  static std::expected<HistoryReader, std::string> open(const std::string& path);
  explicit HistoryReader(Connection db) : db_(std::move(db)) {}

  // Every run, oldest first.
  std::vector<RunSummary> runs();
  // One run; nullopt if there is none with that id.
  std::optional<RunSummary> run(int64_t id);
  // The newest run's id, 0 if there is none.
  int64_t lastRunId();

  std::vector<SignalInfo> signals(int64_t run);
  // The run's devices (index = ActivityRecord::device) and labels (ActivityRecord::label).
  std::vector<DeviceInfo> devices(int64_t run);
  std::vector<std::string> labels(int64_t run);
  // The changes with range.fromNs <= time <= range.toNs in trace order (time, then signal),
  // each passed to `fn`; stops early when fn returns false. Uses the (run, t_ns) key.
  void forEachChange(int64_t run, TimeRange range, const std::function<bool(const SignalChange&)>& fn);
  std::vector<SignalChange> changes(int64_t run, TimeRange range);
  // Each signal's value just before range.fromNs (its initial value if it did not change before).
  std::vector<uint64_t> valuesBefore(int64_t run, int64_t fromNs);
  // A plot of `signals` over `range` with at most about `maxPoints` points each: the changes of
  // a signal with more than maxPoints of them are cut into maxPoints / 3 buckets of equal time,
  // each keeping its smallest, largest and last change (in time order, each once), so a spike
  // survives and the value held after a bucket is right. One search of the (run, t_ns) key over
  // the range; memory bounded by maxPoints per signal. Signals the run does not have are left
  // out; a range beyond the recorded end is cut at it.
  std::vector<Series> series(int64_t run, const std::vector<TagId>& signals, TimeRange range, size_t maxPoints);
  // The activities overlapping the range (start <= toNs, end >= fromNs or still running), in
  // start order, with endNs -1 for one that had not ended. Uses the (run, start_ns) index.
  std::vector<ActivityRecord> activities(int64_t run, TimeRange range);
  // The shifts a monitored run worked against its plan, in time order (none for other runs).
  std::vector<ProductionRow> production(int64_t run);
  // The run's audited writes from outside in the order they landed, within `range`, as the audit
  // made them (writer, variable, old and new value); a row whose protocol or peer does not read
  // back (a file edited by hand) keeps the writer's defaults.
  std::vector<WriteRecord> writes(int64_t run, TimeRange range);

  // The run as a Trace, as `virtcom run` had it at its end, for the report writers: the whole
  // run gives the same VCD, CSV and JSON as the run wrote. A part of a run is shifted to start
  // at 0 (times relative to range.fromNs): initial values are those just before fromNs, changes,
  // activities (clipped to the range), collisions, faults and cycles those inside it, device
  // totals summed from the clipped activities. Empty trace (no signals) if the run is unknown.
  // Rows naming a signal, device or label the run does not have (a file edited or damaged in
  // a way the integrity check cannot see) are left out, so every report writer can take the
  // trace; `skipped` (if given) receives their number.
  Trace trace(int64_t run, TimeRange range = {}, size_t* skipped = nullptr);

 private:
  Connection db_;
};

}  // namespace virtcom::history
