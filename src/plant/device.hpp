#pragma once
// A simulated device: a named component whose ports have exactly the signals of the real device
// (execute/done/error/procedureNumber, actual positions, sensor outputs, ...). The cell loader
// creates one tag per port ("Robot1.execute") and wires tags to PLC variables; the simulation
// calls step() every tick after the PLC scan.
#include <climits>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/config_node.hpp"
#include "core/tag_bus.hpp"
#include "core/trace.hpp"
#include "plant/world.hpp"

namespace virtcom::plant {

enum class PortDir : uint8_t {
  In,   // written by the controller (PLC) — the device reads it
  Out,  // written by the device — the controller reads it
};

struct PortSpec {
  std::string name;   // "execute", "procedureNumber", "actualPosition"
  ElemType type = ElemType::Bool;
  PortDir dir = PortDir::In;
  std::string doc;    // one line for docs/cell-file.md and `virtcom devices`
};

struct StepContext {
  int64_t nowNs = 0;   // virtual time of this tick
  int64_t dtNs = 0;    // since the previous tick
  TagBus& bus;
  World& world;
  Trace& trace;
};

// Injected faults, configured by scenarios (and the cell file's `faults:` entries).
struct FaultPlan {
  int32_t errorCode = 0;        // non-zero: the Nth procedure/command fails with this code
  uint32_t errorAtCommand = 0;  // 1-based command count at which errorCode is raised
  int64_t extraDelayNs = 0;     // every command takes this much longer (late done)
  bool doneStuck = false;       // done never rises (timeout scenarios)
  int stuckOutput = -1;         // sensors: -1 normal, 0 stuck at 0, 1 stuck at 1
};

class Device {
 public:
  Device(std::string name, std::string type) : name_(std::move(name)), type_(std::move(type)) {}
  virtual ~Device() = default;
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  const std::string& name() const { return name_; }
  const std::string& type() const { return type_; }
  const std::vector<PortSpec>& ports() const { return ports_; }
  void bindPort(size_t port, TagId tag) { tags_[port] = tag; }
  TagId tag(size_t port) const { return tags_[port]; }
  // Port index by name, or -1.
  int portIndex(const std::string& name) const;

  // Once before the run: register with the trace (sets traceIndex()), intern labels/facts/zones.
  virtual void prepare(World& world, Trace& trace);
  // Every tick after the PLC scan: read inputs from the bus, advance the model to ctx.nowNs,
  // write outputs. Never allocates (amortised trace appends excepted), never throws.
  virtual void step(const StepContext& ctx) = 0;
  // After step(): the earliest time at which the device, its inputs and the world staying as they
  // are, would change anything (an output, the trace, the world, its energy) on its own: the end
  // of a motion, a procedure step, a timer; INT64_MAX if it only reacts to inputs; a time not
  // after its last step (0) while it varies every tick (ramping outputs, per-tick integration).
  // Event-driven time (sim::SimOptions::eventTime) skips the ticks before it, so a time later than
  // the real change breaks the equivalence with stepping every tick; an earlier one only costs
  // speed. The default steps every tick: a device type skips only once it is shown exact.
  virtual int64_t nextEventNs() const { return 0; }
  // Once at the end: energy and busy-time totals into trace.totals[traceIndex()].
  virtual void finish(int64_t endNs, Trace& trace);
  // Non-zero while the device reports an error to the controller.
  virtual int32_t errorCode() const { return 0; }
  // A mid-run parameter change (a scenario's `parameter:` step, docs/scenarios.md): whether this
  // type can take a new value of its cell-file key `key` (the first key of the changed path:
  // "max_speed", "programs") from `edited`, a device of its type built from its cell-file entry
  // with one scalar value edited (so its lists have the same entries); if so, swapParameters()
  // exchanges the two devices' parameters without allocating, keeping this device's state, the
  // labels interned at prepare() and a running command on its entry. What has begun (a planned
  // motion, a running press stroke) goes on as planned; what begins from then on uses the new values.
  virtual bool changesParameter(std::string_view key) const {
    (void)key;
    return false;
  }
  virtual void swapParameters(Device& edited) { (void)edited; }

  FaultPlan& faults() { return faults_; }
  // Device-specific keys of the cell file's `faults:` entry, after the loader has read the
  // generic FaultPlan keys (drives: `inject`, `comm_loss`). Reports through `faults`.
  virtual void readFaults(ConfigReader& faults) { (void)faults; }
  // Gantt lane group (the cell file's `group:`), read by prepare(); set by createDevice.
  void setGroup(std::string group) { group_ = std::move(group); }
  uint32_t traceIndex() const { return traceIndex_; }

 protected:
  size_t addPort(std::string name, ElemType type, PortDir dir, std::string doc);
  FaultPlan faults_;
  uint32_t traceIndex_ = 0;
  std::string group_;  // Gantt group, optional

 private:
  std::string name_;
  std::string type_;
  std::vector<PortSpec> ports_;
  std::vector<TagId> tags_;
};

// One row of a device-type table: cell-file type name, one-line description, factory.
// A factory reports every mistake of the entry through `cfg` and still returns its device, built
// from what it could read (the readers' fallbacks where a value is unreadable), so that the
// wiring of an entry with parameter mistakes is checked in the same run. Device constructors
// therefore accept any parameter values: nothing is sized or indexed by an unchecked parameter.
using DeviceFactory = std::unique_ptr<Device> (*)(const std::string& name, ConfigReader& cfg, World& world);
struct DeviceType {
  const char* name;
  const char* doc;
  DeviceFactory factory;
};

// Creates a device of `type` from its cell-file entry; reports every problem through `cfg`
// (file:line:col) and returns null only if the type is unknown. An entry with mistakes still
// yields its device, for checking the rest of the entry (wiring, maps); it must not be
// simulated: a caller runs nothing while `cfg.diags()` has errors. `extra` adds the types of
// higher layers (the drives library's table) to this library's own.
std::unique_ptr<Device> createDevice(const std::string& type, const std::string& name, ConfigReader& cfg, World& world,
                                     std::span<const DeviceType> extra = {});
// The registered device types with a one-line description each (for errors and docs).
std::vector<std::pair<std::string, std::string>> deviceTypes();

}  // namespace virtcom::plant
