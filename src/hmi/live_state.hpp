#pragma once
// The running cell as the HMI sees it, shared between the simulation's thread and the HTTP
// threads without ever making the simulation wait:
//  - the simulation publishes: as a TraceSink, after a tick, at most every kPublishPeriodNs of
//    wall time, it copies what the page shows (signal values, new and ended activities, faults,
//    collisions, cycles, the PLC's memory) into a Snapshot, under a try_lock: if an HTTP thread
//    holds the snapshot at that moment the copy waits for a later tick, the scan never does;
//  - the HTTP threads read the Snapshot (read(), a short copy under the lock) and queue Commands
//    (post()), which the simulation applies between two ticks (RunControl::beforeTick), where it
//    also waits while paused;
//  - forced PLC variables are written before and after every scan (beforeScan/afterScan, hooked
//    into sim::SimOptions by the caller), so neither the program nor the wiring changes them.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "cell/cell.hpp"
#include "core/trace.hpp"
#include "plant/conveyor.hpp"
#include "plc/rule_counter.hpp"
#include "plc/runtime.hpp"
#include "core/write_audit.hpp"
#include "sim/run_control.hpp"

namespace virtcom::hmi {

// The parts on one conveyor's belt, as the layout draws them.
struct BeltParts {
  uint32_t device = 0;          // index into Cell::devices
  std::vector<int32_t> positionMm;  // each part's upstream edge along the belt
  std::vector<uint8_t> kind;        // its kind (index into the conveyor's part kinds)
};

// Where a station (a device of the trace) stands: the operation it is in, or idle, and since
// when (the elapsed times per station of docs/monitor.md, live).
struct Station {
  int32_t label = -1;           // its running operation (index into Trace::labels); -1: idle
  int64_t sinceNs = 0;          // virtual time it started, or (idle) the last one ended
  bool operator==(const Station&) const = default;
};

// Production against the plan in the current shift (virtcom monitor with a `plan:`).
struct ShiftProgress {
  std::string shift;   // empty: between shifts
  double planNow = 0;  // the shift's plan pro-rated to the part watched, up to now
  uint32_t parts = 0;  // parts made in it
};

// What the HMI shows, as of one published tick. Sizes are fixed at begin() except the lists
// that grow with the run (activities, faults, collisions), which only append, and the parts on
// the belts, which keep their largest size.
struct Snapshot {
  uint64_t seq = 0;             // +1 per publication
  uint32_t run = 0;             // +1 per reset: viewers drop what they show of the previous run
  int64_t nowNs = 0;            // virtual time of the last tick run
  bool paused = false;
  bool ended = false;
  double speed = 0;             // pace factor
  uint64_t lateTicks = 0;       // ticks so far that started late (sim::Simulation::lateTicks)
  std::string endMessage;       // once ended
  std::vector<uint64_t> tags;   // raw value per TagId (TagBus representation)
  ActivityLog activities;       // bounded as the trace's (core/trace_logs.hpp)
  std::vector<Station> stations;    // per trace device, sized at begin()
  std::vector<FaultRecord> faults;
  std::vector<CollisionRecord> collisions;
  uint32_t cyclesCompleted = 0;
  int64_t lastCycleNs = 0;      // duration of the last completed cycle, 0 before the first
  int64_t cycleStartNs = 0;     // start of the running cycle
  double energyJ = 0;           // energy of the operations finished so far
  std::vector<uint8_t> memory;  // the soft PLC's variables (Module::staticSize bytes), empty without one
  std::vector<std::string> forced;  // names of the forced variables, in forcing order
  std::vector<int32_t> injected;    // per device: the injected error code, 0 = none
  std::vector<plc::RuleFiring> rules;  // per watched rule (LiveState::watchRules), in its order
  std::vector<BeltParts> belts;     // per conveyor, in device order
  bool planned = false;             // a production plan is watched: `shift` is meaningful
  ShiftProgress shift;
};

// A request from an HTTP thread, applied on the simulation's thread between two ticks. Values
// are already parsed (the bytes of the variable's type), so applying one never parses text.
struct Command {
  enum class Kind : uint8_t { Pause, Run, Step, Speed, Write, Release, Fault, Reset };
  Kind kind = Kind::Pause;
  double value = 0;              // Speed: the factor; Step: the tick count
  bool force = false;            // Write: keep writing it before and after every scan
  std::string name;              // Write/Release: the variable (Release: empty = all)
  bc::VarRef ref;                // Write: where (bit included)
  std::vector<uint8_t> bytes;    // Write: the value, the type's size (a BOOL bit: bit `ref.bit` of byte 0)
  ExternalWriter writer{WriteProtocol::Http};  // Write: the HTTP client, as the write is audited
  uint32_t device = 0;           // Fault: index into Cell::devices
  int32_t code = 0;              // Fault: error code, 0 clears
};

class LiveState final : public TraceSink, public sim::RunControl {
 public:
  static constexpr int64_t kPublishPeriodNs = 50'000'000;

  // `cell` and `interrupt` (may be null) must outlive this (or the next restart()).
  // `startPaused`: the first tick waits for run or step.
  LiveState(cell::Cell& cell, const std::atomic<bool>* interrupt, bool startPaused = false);

  // Before the run: count the firings of these activity-diagram rules after every scan (their
  // fired flags, addresses resolved once, so the scan looks nothing up), with the counter the
  // reports use. `taskCount`: the module's tasks.
  void watchRules(std::vector<plc::CountedRule> rules, size_t taskCount);
  // Before the run: every write and force from the page is reported to `audit` (which must
  // outlive this) as it lands, with the client's address (docs/security.md, Audit of external
  // writes). The forced value written again around each scan is not a new write.
  void auditWrites(WriteAudit* audit) { audit_ = audit; }

  // ---- the simulation's thread, between runs ----
  // After a run that ended on a reset (resetting()): the fresh `cell` (the same cell file, the
  // same PLC module object) is watched from now on; the snapshot starts over (time 0, no
  // activities, faults, forces or firings) under a new `run` number, pause and speed are kept.
  void restart(cell::Cell& cell);
  // After the run ended by itself: true (once) if a reset was asked for since; the commands
  // before it are dropped (there is no run to apply them to).
  bool takeReset();

  // ---- the simulation's thread ----
  void begin(const Trace& trace) override;
  void change(const SignalChange&) override {}  // values are read from the bus when publishing
  void tick(const Trace& trace, int64_t nowNs) override;
  void end(const Trace& trace) override;
  bool beforeTick(sim::Simulation& sim) override;
  bool resetting() const override { return resetting_; }
  // Around every scan of the soft PLC (sim::SimOptions::beforeScan/afterScan): the forced
  // values; after it, the rules that fired.
  void beforeScan(plc::Runtime& plc) { applyForces(plc); }
  void afterScan(plc::Runtime& plc) {
    applyForces(plc);
    rules_.count(plc);
  }

  // Before the run: `fill` updates the shift's progress in place at each publication, on the
  // simulation's thread (virtcom monitor with a plan). Without it the snapshot has none.
  void watchShifts(std::function<void(ShiftProgress&)> fill) { shiftProgress_ = std::move(fill); }
  // Before the run, without a soft PLC: the snapshot's PLC memory is copied from `image`
  // (`size` bytes, laid out as the cell's program; updated on the simulation's thread, e.g. the
  // real PLC's SFC flags virtcom monitor reads), so the panels that read it work unchanged.
  void mirrorMemory(const uint8_t* image, size_t size) {
    mirror_ = image;
    mirrorSize_ = size;
  }

  // ---- any thread ----
  void post(Command command);
  // Calls f(const Snapshot&) under the snapshot's lock: keep it short (copy what is needed).
  template <class F>
  void read(F&& f) const {
    std::lock_guard lock(snapshotMutex_);
    f(snapshot_);
  }

 private:
  struct Forced {
    std::string name;
    bc::VarRef ref;
    std::vector<uint8_t> bytes;
  };
  // True if the snapshot was updated (false: a reader held it; try again later).
  bool publish(const Trace& trace, bool wait);
  void mirrorTrace(const Trace& trace);
  void followStation(const ActivityRecord& a);
  void applyCommands(sim::Simulation& sim);
  void apply(Command& c, sim::Simulation& sim);
  void applyForces(plc::Runtime& plc);
  // Runs write(), which lands `value`, between the audit's before and after looks (if audited).
  template <class Write>
  void audited(const ExternalWriter& writer, const Forced& value, Write&& write);
  void copyBelts();
  static bool writeBytes(const Forced& f, uint8_t* memory);

  cell::Cell* cell_;
  const std::atomic<bool>* interrupt_;
  const Trace* trace_ = nullptr;
  plc::Runtime* plc_ = nullptr;
  const uint8_t* mirror_ = nullptr;  // the PLC memory without a soft PLC (mirrorMemory)
  size_t mirrorSize_ = 0;

  // simulation thread only
  bool paused_;
  uint64_t stepsLeft_ = 0;       // ticks to run before pausing again
  bool dirty_ = false;           // something changed that is not published yet
  int64_t nowNs_ = 0;            // the last tick's virtual time
  int64_t lastPublishWallNs_ = 0;
  double speed_ = 0;
  uint64_t lateTicks_ = 0;
  std::vector<Forced> forced_;
  std::vector<Command> applying_;
  std::vector<uint32_t> open_;   // indices of activities still running in the snapshot
  bool resetting_ = false;       // a reset was applied: the run ends at this tick
  bool rebound_ = false;         // restart() since the last tick: the new simulation takes speed_
  plc::RuleCounter rules_;
  std::vector<const plant::Conveyor*> conveyors_;  // parallel to snapshot_.belts
  std::function<void(ShiftProgress&)> shiftProgress_;
  WriteAudit* audit_ = nullptr;

  // HTTP threads -> simulation thread
  std::mutex commandMutex_;
  std::condition_variable commandReady_;
  std::vector<Command> commands_;
  std::atomic<bool> hasCommands_{false};

  mutable std::mutex snapshotMutex_;
  Snapshot snapshot_;
};

}  // namespace virtcom::hmi
