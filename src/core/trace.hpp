#pragma once
// What a simulation run leaves behind: signal changes, device activities (the Gantt bars),
// collisions, faults and per-device totals. The simulation and the devices append to it; reports
// read only this. Appends are amortised O(1); labels are interned at load time so recording an
// activity on the per-tick path never builds a string.
// Nothing in it grows without bound with simulated time: every signal change streams to
// TraceSinks (VCD/CSV files, live views) as the run goes, and a run may keep in `Trace::changes`
// only the signals a report needs (sim::SimOptions::keptSignals); activities and cycles keep the
// first and last of a long run and aggregates of the middle (core/trace_logs.hpp, bounded by
// setWindow). Collisions and faults end a run or are rare, so they are all kept.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/external_write.hpp"
#include "core/iec_value.hpp"
#include "core/tag_bus.hpp"
#include "core/trace_logs.hpp"

namespace virtcom {

struct SignalInfo {
  std::string name;
  ElemType type = ElemType::Bool;
  uint64_t initial = 0;   // raw value (TagBus representation) at time 0
};

struct SignalChange {
  int64_t timeNs = 0;
  TagId tag = 0;
  uint64_t raw = 0;
};

struct DeviceInfo {
  std::string name;
  std::string type;       // "robot", "axis", "press", ...
  std::string group;      // Gantt lane group, e.g. "Robots"; empty = by type
};

struct CollisionRecord {
  int64_t timeNs = 0;
  uint32_t zone = 0;      // index into Trace::labels (zone name)
  uint32_t deviceA = 0, deviceB = 0;
  uint32_t activityA = 0, activityB = 0;  // labels of what each was doing
};

struct FaultRecord {
  int64_t timeNs = 0;
  std::string source;     // device or "PLC"
  std::string message;
};

struct DeviceTotals {
  int64_t busyNs = 0;
  double energyJ = 0;     // all energy, idle included
};

struct Trace;

// Follows a run as it happens (VCD/CSV files, the historian, live views). begin() is called once
// the signals and their initial values are known (before the first change); change() for every
// signal change, in trace order; tick() after every base tick, once that tick's changes were
// delivered, with the trace as the tick left it (activities begun or ended, collisions, faults and
// cycles so far: a sink that follows them keeps its own position); end() when the run has ended
// (Trace::endNs set). change() and tick() are on the per-tick path: they must not throw, and
// should not allocate beyond amortised buffering.
class TraceSink {
 public:
  virtual ~TraceSink() = default;
  virtual void begin(const Trace& trace) = 0;
  virtual void change(const SignalChange& c) = 0;
  virtual void tick(const Trace& trace, int64_t nowNs) {
    (void)trace;
    (void)nowNs;
  }
  virtual void end(const Trace& trace) = 0;
};

enum class RunEnd { Completed, TimeLimit, PlcFault, DeviceError, Collision, Interrupted };
const char* runEndName(RunEnd e);

// How the simulation's clock went: base ticks in all, and those passed without stepping by
// event-driven time (sim::SimOptions::eventTime) in how many jumps.
struct TimeSteps {
  bool eventDriven = false;
  uint64_t ticks = 0;
  uint64_t ticksSkipped = 0;
  uint64_t jumps = 0;
  // A run paced to the wall clock: the ticks that started late (the wall clock already past their
  // due time: the work before them overran it, PacedClock::lateTicks) and the latest such start.
  bool paced = false;
  uint64_t lateTicks = 0;
  int64_t maxLateNs = 0;
};

struct Trace {
  std::vector<SignalInfo> signals;        // indexed by TagId
  std::vector<SignalChange> changes;      // in time order; all, or only the kept signals'
  std::vector<DeviceInfo> devices;
  std::vector<std::string> labels;
  ActivityLog activities;                 // in start order; indices are beginActivity's
  std::vector<CollisionRecord> collisions;
  std::vector<FaultRecord> faults;
  std::vector<DeviceTotals> totals;       // per device, filled at the end of the run
  int64_t endNs = 0;
  int64_t cycleStartNs = 0;               // the measured cycle (whole run if no markers)
  int64_t cycleEndNs = 0;
  uint32_t cyclesCompleted = 0;
  CycleLog cycles;                        // completed cycles in order; the last is the measured one
  RunEnd end = RunEnd::Completed;
  std::string endMessage;
  TimeSteps time;
  // The writes from outside (protocol clients, the HMI) into the soft PLC, when they were audited
  // (docs/security.md; `serve`, `run --hmi` and a recorded run's export fill it): the count per
  // protocol, and the first kKeptWriteRecords of them in order for the HTML report's table (a
  // client writing every scan of a run that serves for days must not grow the trace).
  bool writesAudited = false;
  std::array<uint64_t, kWriteProtocolCount> externalWrites{};
  std::vector<WriteRecord> writeRecords;
  static constexpr size_t kKeptWriteRecords = 1000;

  // Before the run: keep every activity and every cycle while there are at most `limit` of each,
  // beyond that the first and the last limit/2 (kDefaultTraceWindow unless set).
  void setWindow(size_t limit);
  // Load time: label ids for operation, procedure and zone names.
  uint32_t internLabel(const std::string& label);
  uint32_t addDevice(std::string name, std::string type, std::string group = {});
  // Per tick: start/finish an activity; returns the activity index.
  uint32_t beginActivity(uint32_t device, uint32_t label, int64_t nowNs);
  void endActivity(uint32_t activity, int64_t nowNs, double energyJ, int32_t errorCode = 0);
  // An audited write: counted, and kept while fewer than kKeptWriteRecords are. Allocates (the
  // record's copy) only while it keeps.
  void keepExternalWrite(const WriteRecord& record);
};

}  // namespace virtcom
