#pragma once
// The PLC-device handshake of seed Table 2 / Figure 6 / Algorithm 3, shared by every device
// that executes numbered commands (robot, axis, press, timed).
//
// Ports (in this order, then the subclass's): <command> (IN: procedureNumber INT,
// programNumber INT or targetPosition LREAL mm), execute (IN BOOL), done (OUT BOOL),
// error (OUT INT, 0 = none), busy (OUT BOOL).
//
// Timing, one state per line (t = the tick at which step() runs):
//   Idle      done = 0. When execute = 1 (level) the command is read at this tick:
//             unknown -> error := 10, no procedure (WaitDrop); injected fault -> error := code;
//             precondition refused at start (limits, missing insert...) -> error := code;
//             otherwise busy := 1 and the command starts at t.
//   Running   the model advances in exact virtual time; the command ends at its computed end
//             time E and the device reports at the first tick with time >= E: done := 1,
//             busy := 0. A failure during the command: error := code, busy := 0, no done.
//             execute is not read while running: a new execute is ignored, and dropping
//             execute does NOT abort the command (a robot never aborts a motion); done still
//             rises at the end and, execute being 0 already, drops at the next tick (the
//             `while execute != 0` loop of Algorithm 3 exits at once).
//   Delaying  only with FaultPlan::extraDelayNs: done rises extraDelayNs after E.
//   WaitDrop  done (or error) held until execute = 0; then done := 0, error := 0 -> Idle.
// FaultPlan: errorCode at command number errorAtCommand (1-based count of every command
// read, unknown ones included; 0 = every command) is raised at the start like a refusal, without
// touching the world; extraDelayNs delays every done; doneStuck: the command completes (busy
// drops) but done never rises.
// Trace: one activity per command read, from the start tick to the done/error tick, with the
// command's energy and error code (unknown numbers use the label "UnknownCommand").
// Energy totals: idle power x whole run + the sum of the commands' energies.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "plant/device.hpp"
#include "plant/device_errors.hpp"

namespace virtcom::plant {

class SequencedDevice : public Device {
 public:
  static constexpr uint32_t kNoLabel = 0xffffffffu;
  enum PortIndex : size_t { kCommandPort = 0, kExecutePort, kDonePort, kErrorPort, kBusyPort, kFirstModelPort };

  void prepare(World& world, Trace& trace) override;
  void step(const StepContext& ctx) final;
  int64_t nextEventNs() const final;
  void finish(int64_t endNs, Trace& trace) override;
  int32_t errorCode() const override { return error_; }

  bool done() const { return done_; }
  bool busy() const { return phase_ == Phase::Running || phase_ == Phase::Delaying; }
  uint32_t commandsRead() const { return commandCount_; }
  // The label an activity of `command` gets (its name, or "UnknownCommand"), for whoever
  // records this device's operations from outside (sim/operation_recogniser.hpp). After prepare().
  uint32_t operationLabel(double command) const {
    const uint32_t label = commandLabel(command);
    return label == kNoLabel ? unknownLabel_ : label;
  }

 protected:
  SequencedDevice(std::string name, std::string type, std::string commandPort, ElemType commandType,
                  std::string commandDoc);

  enum class Progress : uint8_t { Running, Finished, Failed };

  // Label of a known command (interned at prepare), kNoLabel if the command is unknown.
  virtual uint32_t commandLabel(double command) const = 0;
  // Starts a known command at `startNs`; 0, or an error code refusing it (no procedure runs).
  // Resets the command's energy.
  virtual int32_t beginCommand(double command, int64_t startNs, const StepContext& ctx) = 0;
  // Advances the running command to ctx.nowNs. Finished: `atNs` = exact end time (<= now).
  // Failed: `error` = code. Never allocates.
  virtual Progress advance(const StepContext& ctx, int64_t& atNs, int32_t& error) = 0;
  // Energy (J) of the current/last command so far.
  virtual double commandEnergyJ() const = 0;
  // While a command runs: when the model next changes anything on its own (the end of its
  // current step or motion), or 0 while its outputs change every tick (a ramp, a move).
  virtual int64_t modelNextEventNs() const = 0;
  // Writes the model's own outputs (positions, forces...) for ctx.nowNs.
  virtual void writeOutputs(const StepContext& ctx) = 0;
  // Subclass labels (procedure names...), called from prepare().
  virtual void prepareLabels(World& world, Trace& trace) = 0;

  double idlePowerW_ = 0;

  // swapParameters() of a subclass whose Params hold the entries of `list` (procedures,
  // programs): swaps `mine` and `edited` (same entries, one scalar differs), keeping the labels
  // interned at prepare() and `running` on the same entry; the idle power follows the new values.
  template <class Params, class Entry>
  void swapKeepingLabels(Params& mine, Params& edited, std::vector<Entry> Params::*list, const Entry*& running) {
    std::vector<Entry>& from = mine.*list;
    std::vector<Entry>& to = edited.*list;
    for (size_t i = 0; i < from.size() && i < to.size(); ++i) to[i].label = from[i].label;
    const ptrdiff_t at = running ? running - from.data() : -1;
    std::swap(mine, edited);
    if (at >= 0) running = (mine.*list).data() + at;
    idlePowerW_ = mine.idlePowerW;
  }

 private:
  enum class Phase : uint8_t { Idle, Running, Delaying, WaitDrop };
  void startCommand(const StepContext& ctx);
  void progress(const StepContext& ctx);
  void complete(const StepContext& ctx);
  void fail(const StepContext& ctx, int32_t error, double energyJ);

  Phase phase_ = Phase::Idle;
  bool done_ = false;
  bool execute_ = false;
  int32_t error_ = 0;
  uint32_t commandCount_ = 0;
  uint32_t activity_ = 0;
  uint32_t unknownLabel_ = 0;
  int64_t startNs_ = 0;
  int64_t delayEndNs_ = 0;
  int64_t lastStepNs_ = 0;
  int64_t busyNs_ = 0;
  double energySumJ_ = 0;
};

}  // namespace virtcom::plant
