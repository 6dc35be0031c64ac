#pragma once
// The co-simulation engine: one integer-nanosecond virtual clock for the PLC tasks, the devices
// and the recorders, stepped in a fixed order every PLC base tick:
//   1. device outputs -> PLC variables (wires), 2. PLC scan (all tasks due), 3. PLC variables ->
//   device inputs, 4. bridges pull (external controller -> command signals), 5. devices step
//   (in cell-file order), 6. bridges push (status signals -> external side), 7. recorder stores
//   changed signals, 8. stop conditions (until, cycles, faults, collisions, time limit).
// A cell without a soft PLC (no module: its controller is external) skips 1-3 and ticks at the
// cell's plc cycle time; its cycles are counted on the tag of run.cycleDoneTag (a variable of
// the external PLC that a bridge reads), if any.
// Watching a real plant (SimOptions::watch, `virtcom monitor`), step 5 is replaced: the devices do
// not step, the bridges bring their ports' values and an OperationRecogniser records their
// operations.
// The same cell and options give the same trace, byte for byte.
#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cell/cell.hpp"
#include "core/bus_bridge.hpp"
#include "core/clock.hpp"
#include "plc/runtime.hpp"
#include "sim/operation_recogniser.hpp"
#include "sim/run_control.hpp"

namespace virtcom::sim {

struct SimOptions {
  double speed = 0;                 // 0: as fast as possible; else paced (1 = real time)
  int64_t timeLimitNs = -1;         // overrides the cell's run.time_limit when >= 0
  const std::atomic<bool>* interrupt = nullptr;  // set asynchronously to stop (SIGINT)
  // Called once after the PLC's cold start, before the first scan (e.g. `--set` presets).
  std::function<void(plc::Runtime& plc)> preset;
  // Skip PLC scans that provably repeat the previous one (exact: same results and trace).
  bool skipRepeatedScans = true;
  // Event-driven time: run() jumps over the ticks in which nothing can change (see
  // Simulation::skipIdleTicks), with the same results as stepping every tick. Only unpaced runs
  // without bridges, RunControl, watch or scan hooks jump: those can change state from outside.
  bool eventTime = true;
  // Links to external peers (Modbus/ADS), stepped in this order; they must outlive the run.
  // A failed pull() ends the run as a PLC fault (the external PLC is the controller).
  std::vector<BusBridge*> bridges;
  // Around every scan of the soft PLC, on the simulation's thread (an ADS server serving it:
  // queued writes and RUN/STOP before, the image snapshot after; its first snapshot is taken
  // in `preset`). afterScan runs once the scan's outputs are on the bus. Must not allocate.
  std::function<void(plc::Runtime& plc)> beforeScan, afterScan;
  // afterScan is only an observer that accounts for the scans a jump of event-driven time
  // passed over itself (from the task's scan count, as plc::RuleCounter does): it does not
  // keep the clock from jumping.
  bool afterScanSeesJumps = false;
  // Follow the run as it goes: every recorded signal change, every tick, the end (core/trace.hpp;
  // they must outlive the run). What a stop condition adds in the last tick (a fault) reaches end().
  std::vector<TraceSink*> traceSinks;
  // Which changes stay in Trace::changes for the whole run: all of them, or (keepAllChanges =
  // false) only those of the signals named in keptSignals (e.g. the report's timeline; unknown
  // names are ignored here), so a long run's memory stays bounded.
  bool keepAllChanges = true;
  std::vector<std::string> keptSignals;
  // How many activities and cycles Trace keeps: all while there are at most this many, beyond
  // that the first and the last half (Trace::setWindow, docs/report.md "Long runs").
  size_t traceWindow = kDefaultTraceWindow;
  // Machine code for the soft PLC's module (src/aot); null runs the interpreter.
  std::shared_ptr<const vm::CompiledCode> compiled;
  // Tiered execution (`--backend auto`): machine code compiled while the run goes, switched to
  // between two scans once published (plc::Runtime::switchToCompiledWhenReady); null: none.
  std::shared_ptr<const vm::CompiledHandoff> tierUp;
  // Steers the run before every tick (pause, step, speed; must outlive the run). A controlled
  // run is always paced (speed 0 means 1), so that its speed can change while it runs.
  RunControl* control = nullptr;
  // The plant is real: its devices' ports come from bridges, their operations are recognised
  // from the handshake and compared with `model`, a finished simulated run of the same cell
  // (null: not compared; read in the constructor).
  struct Watch {
    bool enabled = false;
    const Trace* model = nullptr;
    double threshold = 0.2;  // relative deviation that raises an alert
  } watch;
};

class Simulation {
 public:
  // The cell must outlive the simulation. Prepares devices and the trace (load time).
  Simulation(cell::Cell& cell, SimOptions options);
  ~Simulation();

  // Cold-starts the PLC and runs until a stop condition; returns how the run ended (also in
  // the trace). Allocates nothing per tick except amortised trace appends.
  RunEnd run();
  // Advances one base tick (for single stepping; never jumps); false once the run has ended.
  bool step();

  bool hasPlc() const { return runtime_ != nullptr; }
  // Precondition: the cell has a soft PLC.
  plc::Runtime& plc() { return *runtime_; }
  // Controlled runs (SimOptions::control): the pace factor, changeable between ticks; after a
  // pause resumePacing() keeps the paused wall time from counting. No effect on unpaced runs.
  double speed() const { return paced_ ? paced_->speed() : 0; }
  void setSpeed(double speed) {
    if (paced_) paced_->setSpeed(speed);
  }
  void resumePacing() {
    if (paced_) paced_->resume();
  }
  // Paced runs: the ticks so far that started late (PacedClock::lateTicks); 0 unpaced.
  uint64_t lateTicks() const { return paced_ ? paced_->lateTicks() : 0; }

  // A wire as the per-tick transfer needs it: cell::Wire's hot fields in 12 bytes, no name.
  struct WireSlot {
    uint32_t address = 0;
    TagId tag = kNoTag;
    int8_t bit = -1;
    ElemType varType = ElemType::Bool;
  };

  Trace& trace() { return cell_.trace; }
  int64_t nowNs() const { return nowNs_; }
  uint64_t ticks() const { return ticks_; }
  // Watching a real plant (SimOptions::watch): its operations so far; null otherwise.
  const OperationRecogniser* recogniser() const { return recogniser_.get(); }

 private:
  void start();
  bool checkStop();
  bool checkPlcStop();
  bool countCycle(bool done);
  void scanPlc();
  void readFromPlc(const uint8_t* mem);
  bool pullBridges();
  void recordChanges();
  void skipIdleTicks();
  void finish(RunEnd end, std::string message);

  cell::Cell& cell_;
  SimOptions options_;
  std::unique_ptr<Clock> clock_;
  PacedClock* paced_ = nullptr;  // clock_ when paced
  std::unique_ptr<plc::Runtime> runtime_;
  std::unique_ptr<OperationRecogniser> recogniser_;  // watching a real plant
  std::vector<TagId> recordTags_;
  std::vector<uint8_t> keepChange_;      // per tag: 1 = its changes stay in Trace::changes
  std::vector<WireSlot> toPlc_;    // device outputs -> PLC variables
  // Device outputs wired to located inputs (AT %I...), addressed in the PLC's input image: the
  // scan copies that image into the %I area, so a write into the area itself would be lost.
  std::vector<WireSlot> toInputImage_;
  std::vector<WireSlot> fromPlc_;  // PLC variables -> device inputs, then variables recorded as signals
  cell::Wire cycleWire_;
  bool hasCycleWire_ = false;
  bool lastCycleDone_ = false;
  bool cycleTagSeen_ = false;  // run.cycleDoneTag read once (its first level is no edge)
  int64_t lastCycleEdgeNs_ = 0;
  int64_t nowNs_ = 0;
  uint64_t ticks_ = 0;
  bool started_ = false;
  bool ended_ = false;
  bool jumps_ = false;           // event-driven time allowed (SimOptions::eventTime and no outside writer)
  bool tickChanged_ = false;     // the last tick changed a signal or the world
  uint64_t worldChanges_ = 0;    // World::changes() after the previous tick
  int64_t timeLimitNs_ = 0;
};

}  // namespace virtcom::sim
