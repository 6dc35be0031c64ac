#pragma once
// The historian's TraceSink: records a run into a history database (docs/history.md) as it
// goes. On the simulation thread it only copies fixed-size events into a preallocated bounded
// queue (no allocation, no lock, no I/O per change or per tick); a writer thread of its own
// drains the queue into SQLite in batched transactions, committing at least every flush period,
// so the scan never waits for the disk. When the queue is full an event is dropped and counted,
// never silently: drops() and the run's row say how many. A run in virtual time, which has no
// wall-clock deadline, may instead wait for room (RecorderOptions::waitWhenFull) and lose nothing.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <expected>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "core/external_write.hpp"
#include "core/trace.hpp"
#include "history/event_queue.hpp"
#include "history/retention.hpp"
#include "history/run_writer.hpp"
#include "history/sqlite.hpp"

namespace virtcom::history {

struct RecorderOptions {
  std::string cellName;
  std::string cellFile;
  std::vector<std::string> timeline;            // the report's timeline signals
  std::vector<std::string> shiftNames;          // a monitored plant's planned shifts (production()), by index
  size_t queueEvents = 1 << 16;                  // 48 bytes each: 3 MiB
  int64_t flushPeriodNs = 200'000'000;           // longest wall time between commits
  bool waitWhenFull = false;                     // wait for the writer instead of dropping (unpaced runs only)
  Retention retention;                           // applied when opened, then every minute
};

class Recorder final : public TraceSink {
 public:
  // Opens (or creates) the database and applies the retention limits. The error says what is
  // wrong with the file. Blocks on I/O (integrity check, pruning).
  static std::expected<std::unique_ptr<Recorder>, std::string> open(const std::string& path, RecorderOptions options);
  ~Recorder() override;

  // Writes the run's row, signals, devices and labels, then starts the writer thread.
  void begin(const Trace& trace) override;
  void change(const SignalChange& c) override;
  void tick(const Trace& trace, int64_t nowNs) override;
  // Hands over the rest (waiting for room in the queue: the scan is over), stops the writer and
  // writes how the run ended. Blocks until everything is committed.
  void end(const Trace& trace) override;

  // After end(): the shifts a monitored plant worked, against its plan (blocks on I/O). False
  // (and error() says why) on a database failure.
  bool recordProduction(const std::vector<ProductionRow>& rows);
  // While recording, on the simulation thread: the row of one occurrence of the plan's shift
  // `shift` (RecorderOptions::shiftNames) as it stands, written (replacing the previous one of
  // that occurrence) with the writer's next batch, so a killed monitor keeps its production up
  // to the last commit. Never blocks nor allocates; a full queue drops it (counted).
  void production(uint32_t shift, const ProductionEvent& row);

  // While recording, on the simulation thread: one audited write from outside (docs/security.md),
  // a row of the table `writes` with the writer's next batch. Never blocks; a full queue drops it
  // (counted).
  void externalWrite(const WriteRecord& record);

  int64_t runId() const { return run_; }
  // Events the full queue refused so far (a fault's text counts as one event with its fault).
  uint64_t drops() const { return drops_.load(std::memory_order_relaxed); }
  // Empty unless the database failed during the run (disk full, ...): then SQLite's message;
  // events after the failure are lost and counted in drops(). Read after end().
  const std::string& error() const { return error_; }
  // Runs deleted by the retention limits, when opened and during the run.
  int64_t pruned() const { return pruned_.load(std::memory_order_relaxed); }

 private:
  Recorder(Connection db, RecorderOptions options);
  template <class Fill>
  void push(size_t n, bool wait, Fill&& fill);
  void pushActivity(const Trace& trace, uint32_t index, bool wait);
  void pushFault(const Trace& trace, uint32_t index, bool wait);
  // `head` (kind, index, time and its own fields set by head(event)), then `texts` one after the
  // other in text events of kTextChunk bytes.
  template <class Head>
  void pushWithTexts(std::span<const std::string_view> texts, bool wait, Head&& head);
  // Hands over what the trace gained since the last call: activities begun or ended,
  // collisions, faults, a completed cycle.
  void follow(const Trace& trace, bool wait);
  void writerLoop();
  void stopWriter();

  Connection db_;
  RecorderOptions options_;
  RunWriter writer_;
  EventQueue queue_;
  int64_t run_ = -1;

  // Simulation thread only.
  std::vector<uint32_t> openActivities_;
  size_t activitiesSeen_ = 0, collisionsSeen_ = 0, faultsSeen_ = 0;
  uint32_t cyclesSeen_ = 0;
  uint32_t writesSeen_ = 0;

  std::atomic<uint64_t> drops_{0};
  std::atomic<int64_t> progressNs_{0};  // virtual time of the last tick handed over
  std::atomic<int64_t> pruned_{0};
  std::atomic<bool> hurry_{false};  // the simulation waits for room: drain now
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;  // guarded by mutex_
  std::thread thread_;
  std::string error_;  // writer thread until it is joined
};

}  // namespace virtcom::history
