#pragma once
// Operations of a real plant, recognised from the signals its devices share with the PLC
// (`virtcom monitor`, docs/monitor.md): where a simulated device records its own activities,
// a watched one is only seen through its ports, so this records the same activities, with the
// same device and label indices, from the handshake (docs/devices.md "The handshake"):
//   - robot, axis, press, timed: `execute` seen while idle starts an operation labelled with
//     the command (`procedureNumber` / `programNumber` / `targetPosition`) as the cell file
//     names it; `done`, `error` <> 0 or `busy` falling ends it (with the error code). It then
//     waits until `execute`, `done` and `error` are all down before the next one can start;
//   - conveyor: `run` on starts "Running", off ends it.
// A poll that misses a signal shorter than its period misses what only that signal shows
// (a zero-duration command). Each completed operation is compared with what the cell model
// predicts (DurationModel); a deviation beyond the threshold is a fault record in the trace
// (so the HMI, the reports and the historian show it).
// Per poll: no allocation (amortised trace appends and an alert's message excepted), no lookup
// by name.
#include <cstdint>
#include <memory>
#include <vector>

#include "core/tag_bus.hpp"
#include "core/trace.hpp"
#include "plant/device.hpp"

namespace virtcom::sim {

// The durations the cell model predicts for each (device, operation): the range of the completed
// activities of a simulated run (one operation name may be several commands, or take longer at
// one place than another), by device and label name, re-indexed to another trace of the same cell.
class DurationModel {
 public:
  DurationModel() = default;
  // `simulated`: a finished run of the model; `watched`: the trace the monitor records into
  // (its devices and labels interned). Load time.
  DurationModel(const Trace& simulated, const Trace& watched);
  struct Range {
    int64_t minNs = -1, maxNs = -1;  // -1: the model never completed that operation
    bool known() const { return minNs >= 0; }
    // (actual - max) / max above the range, (actual - min) / min below it, 0 within (or unknown).
    double deviation(int64_t actualNs) const;
  };
  Range expected(uint32_t device, uint32_t label) const;
  // The model's cycle time (its last measured cycle), 0 without one.
  int64_t cycleNs() const { return cycleNs_; }

 private:
  size_t labels_ = 0;
  std::vector<Range> expected_;  // device * labels_ + label
  int64_t cycleNs_ = 0;
};

// How the watched operations of one (device, label) compared with the model so far.
struct OperationStats {
  uint32_t device = 0, label = 0;
  uint32_t count = 0;           // completed without error
  int64_t totalNs = 0;          // their summed durations
  DurationModel::Range expected;  // the model's
  double worstDeviation = 0;    // DurationModel::Range::deviation of the farthest one
  uint32_t alerts = 0;          // completions beyond the threshold
};

class OperationRecogniser {
 public:
  // `devices` prepared (labels interned in `trace`); `model`: a finished simulated run of the
  // same cell, read here (null: no comparison); `threshold`: the relative deviation that raises
  // an alert (0.2 = 20 %).
  OperationRecogniser(const std::vector<std::unique_ptr<plant::Device>>& devices, Trace& trace, const Trace* model,
                      double threshold);

  // One poll: the ports' values as the bus holds them now.
  void observe(const TagBus& bus, int64_t nowNs);

  // Per (device, label) seen so far, in the order first completed.
  const std::vector<OperationStats>& stats() const { return stats_; }
  const DurationModel& model() const { return model_; }

 private:
  enum class Phase : uint8_t { Unseen, Idle, Running, WaitDrop };
  struct Watched {
    const plant::Device* device = nullptr;
    uint32_t traceDevice = 0;
    bool conveyor = false;
    TagId command = kNoTag, execute = kNoTag, done = kNoTag, error = kNoTag, busy = kNoTag;  // conveyor: execute = run
    Phase phase = Phase::Unseen;
    bool sawBusy = false;
    bool joined = false;  // the running operation began before the first poll: its start is unknown
    uint32_t activity = 0;
  };

  void observeHandshake(Watched& w, const TagBus& bus, int64_t nowNs);
  void observeConveyor(Watched& w, const TagBus& bus, int64_t nowNs);
  void begin(Watched& w, uint32_t label, int64_t nowNs, bool joined);
  void end(Watched& w, int64_t nowNs, int32_t error);
  void compare(const Watched& w, const ActivityRecord& a);

  Trace& trace_;
  DurationModel model_;  // empty without a model: every expectation unknown
  double threshold_;
  std::vector<Watched> watched_;
  std::vector<OperationStats> stats_;
  std::vector<int32_t> statIndex_;  // device * labels + label -> stats_ index, -1 none yet
};

}  // namespace virtcom::sim
