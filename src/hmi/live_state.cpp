#include "hmi/live_state.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "core/ascii.hpp"
#include "core/clock.hpp"
#include "plc/variable_text.hpp"
#include "sim/simulation.hpp"

namespace virtcom::hmi {

namespace {
// How long a paused simulation sleeps between looks at the command queue and the interrupt.
constexpr auto kPausedPoll = std::chrono::milliseconds(20);
}  // namespace

LiveState::LiveState(cell::Cell& cell, const std::atomic<bool>* interrupt, bool startPaused)
    : cell_(&cell), interrupt_(interrupt), paused_(startPaused) {}

void LiveState::watchRules(std::vector<plc::CountedRule> rules, size_t taskCount) {
  rules_ = plc::RuleCounter(std::move(rules), taskCount);
}

void LiveState::begin(const Trace& trace) {
  trace_ = &trace;
  conveyors_.clear();
  for (const auto& d : cell_->devices)
    if (const auto* conveyor = dynamic_cast<const plant::Conveyor*>(d.get())) conveyors_.push_back(conveyor);
  std::lock_guard lock(snapshotMutex_);
  snapshot_.tags.assign(cell_->bus.size(), 0);
  snapshot_.memory.assign(cell_->module ? cell_->module->staticSize : mirrorSize_, 0);
  snapshot_.injected.assign(cell_->devices.size(), 0);
  if (snapshot_.activities.empty()) snapshot_.activities.setLimit(trace.activities.limit());
  snapshot_.activities.reserve(trace.activities.capacity());
  snapshot_.stations.assign(trace.devices.size(), {});
  snapshot_.rules.assign(rules_.firings().size(), {});
  snapshot_.belts.resize(conveyors_.size());
  for (size_t b = 0; b < conveyors_.size(); ++b)
    snapshot_.belts[b].device = static_cast<uint32_t>(
        std::ranges::find_if(cell_->devices, [&](const auto& d) { return d.get() == conveyors_[b]; }) - cell_->devices.begin());
  open_.reserve(cell_->devices.size() * 2);
}

void LiveState::restart(cell::Cell& cell) {
  cell_ = &cell;
  trace_ = nullptr;
  plc_ = nullptr;
  resetting_ = false;
  rebound_ = true;
  stepsLeft_ = 0;
  nowNs_ = 0;
  open_.clear();
  forced_.clear();  // the PLC starts from its initial values: nothing forced
  rules_.restart();
  std::lock_guard lock(snapshotMutex_);
  Snapshot& s = snapshot_;
  ++s.run;
  ++s.seq;
  s.nowNs = 0;
  s.ended = false;
  s.endMessage.clear();
  s.activities.clear();
  std::ranges::fill(s.stations, Station{});
  s.faults.clear();
  s.collisions.clear();
  s.cyclesCompleted = 0;
  s.lastCycleNs = 0;
  s.cycleStartNs = 0;
  s.energyJ = 0;
  s.forced.clear();
  for (BeltParts& b : s.belts) {
    b.positionMm.clear();
    b.kind.clear();
  }
}

bool LiveState::takeReset() {
  std::lock_guard lock(commandMutex_);
  auto reset = std::ranges::find(commands_, Command::Kind::Reset, &Command::kind);
  if (reset == commands_.end()) return false;
  commands_.erase(commands_.begin(), reset + 1);
  hasCommands_.store(!commands_.empty(), std::memory_order_release);
  return true;
}

void LiveState::tick(const Trace& trace, int64_t nowNs) {
  nowNs_ = nowNs;
  dirty_ = true;
  if (monotonicNowNs() - lastPublishWallNs_ >= kPublishPeriodNs) publish(trace, false);
}

void LiveState::end(const Trace& trace) {
  {
    std::lock_guard lock(snapshotMutex_);
    snapshot_.ended = true;
    snapshot_.endMessage = trace.endMessage;
  }
  nowNs_ = trace.endNs;
  publish(trace, true);
}

bool LiveState::publish(const Trace& trace, bool wait) {
  std::unique_lock lock(snapshotMutex_, std::defer_lock);
  if (wait) lock.lock();
  else if (!lock.try_lock()) return false;
  Snapshot& s = snapshot_;
  ++s.seq;
  s.nowNs = nowNs_;
  s.paused = paused_ && stepsLeft_ == 0;
  s.speed = speed_;
  s.lateTicks = lateTicks_;
  for (TagId id = 0; id < s.tags.size(); ++id) s.tags[id] = cell_->bus.raw(id);
  mirrorTrace(trace);
  if (const uint8_t* memory = plc_ ? plc_->machine().memory() : mirror_; memory && !s.memory.empty())
    std::memcpy(s.memory.data(), memory, s.memory.size());
  for (size_t d = 0; d < s.injected.size(); ++d) s.injected[d] = cell_->devices[d]->faults().errorCode;
  std::ranges::copy(rules_.firings(), s.rules.begin());
  copyBelts();
  s.planned = static_cast<bool>(shiftProgress_);
  if (shiftProgress_) shiftProgress_(s.shift);
  dirty_ = false;
  lastPublishWallNs_ = monotonicNowNs();
  return true;
}

// Appends what the trace gained since the last publication and closes the activities that ended.
void LiveState::mirrorTrace(const Trace& trace) {
  Snapshot& s = snapshot_;
  for (size_t i = 0; i < open_.size();) {
    const ActivityRecord& a = trace.activities[open_[i]];
    s.activities[open_[i]] = a;
    if (a.endNs < 0) {
      ++i;
      continue;
    }
    followStation(a);
    s.energyJ += a.energyJ;
    open_[i] = open_.back();
    open_.pop_back();
  }
  for (size_t i = s.activities.size(); i < trace.activities.size(); ++i) {
    // The snapshot's log has the trace's bound, so what the trace elided before this publication
    // saw it is elided here too as the placeholder's turn passes (a viewer never reads it).
    const ActivityRecord a = trace.activities.held(i) ? trace.activities[i] : ActivityRecord{.endNs = 0};
    s.activities.push_back(a);
    if (a.endNs < 0) open_.push_back(static_cast<uint32_t>(i));
    else s.energyJ += a.energyJ;
    if (trace.activities.held(i)) followStation(a);
  }
  s.faults.insert(s.faults.end(), trace.faults.begin() + static_cast<ptrdiff_t>(std::min(s.faults.size(), trace.faults.size())),
                  trace.faults.end());
  s.collisions.insert(s.collisions.end(),
                      trace.collisions.begin() + static_cast<ptrdiff_t>(std::min(s.collisions.size(), trace.collisions.size())),
                      trace.collisions.end());
  s.cyclesCompleted = trace.cyclesCompleted;
  s.lastCycleNs = trace.cyclesCompleted ? trace.cycleEndNs - trace.cycleStartNs : 0;
  s.cycleStartNs = trace.cyclesCompleted ? trace.cycleEndNs : 0;
}

// The station of `a`'s device after `a` began or ended (activities come in start order, so a
// device's later operation is never overwritten by the end of an earlier one).
void LiveState::followStation(const ActivityRecord& a) {
  if (a.device >= snapshot_.stations.size()) return;
  Station& station = snapshot_.stations[a.device];
  if (a.endNs < 0) station = {static_cast<int32_t>(a.label), a.startNs};
  else if (station.sinceNs <= a.startNs) station = {-1, a.endNs};
}

// The parts' positions in whole millimetres: vectors keep their largest size, so this allocates
// only when a belt carries more parts than it ever did.
void LiveState::copyBelts() {
  for (size_t b = 0; b < conveyors_.size(); ++b) {
    const plant::Conveyor& c = *conveyors_[b];
    BeltParts& out = snapshot_.belts[b];
    out.positionMm.resize(c.partCount());
    out.kind.resize(c.partCount());
    for (size_t i = 0; i < c.partCount(); ++i) {
      out.positionMm[i] = static_cast<int32_t>(std::lround(c.partPositionM(i) * 1000));
      out.kind[i] = c.partKind(i);
    }
  }
}

bool LiveState::beforeTick(sim::Simulation& sim) {
  if (!plc_ && sim.hasPlc()) plc_ = &sim.plc();
  if (speed_ == 0) speed_ = sim.speed();
  lateTicks_ = sim.lateTicks();
  if (rebound_) {
    sim.setSpeed(speed_);  // the speed chosen before the reset
    rebound_ = false;
  }
  if (hasCommands_.load(std::memory_order_acquire)) applyCommands(sim);
  if (resetting_) return false;
  if (paused_ && stepsLeft_ == 0) {
    dirty_ = true;
    while (paused_ && stepsLeft_ == 0 && !resetting_) {
      if (dirty_) publish(*trace_, false);
      if (interrupt_ && interrupt_->load()) return false;
      {
        std::unique_lock lock(commandMutex_);
        commandReady_.wait_for(lock, kPausedPoll, [this] { return hasCommands_.load(); });
      }
      if (hasCommands_.load(std::memory_order_acquire)) applyCommands(sim);
    }
    if (resetting_) return false;
    sim.resumePacing();  // the paused wall time does not count
  }
  if (stepsLeft_ > 0) --stepsLeft_;
  return true;
}

void LiveState::post(Command command) {
  {
    std::lock_guard lock(commandMutex_);
    commands_.push_back(std::move(command));
    hasCommands_.store(true, std::memory_order_release);
  }
  commandReady_.notify_one();
}

void LiveState::applyCommands(sim::Simulation& sim) {
  {
    std::lock_guard lock(commandMutex_);
    applying_.swap(commands_);
    hasCommands_.store(false, std::memory_order_release);
  }
  for (Command& c : applying_) apply(c, sim);
  applying_.clear();
  dirty_ = true;
}

void LiveState::apply(Command& c, sim::Simulation& sim) {
  switch (c.kind) {
    case Command::Kind::Pause: paused_ = true; stepsLeft_ = 0; break;
    case Command::Kind::Run: paused_ = false; stepsLeft_ = 0; break;
    case Command::Kind::Step: paused_ = true; stepsLeft_ = static_cast<uint64_t>(c.value); break;
    case Command::Kind::Speed:
      sim.setSpeed(c.value);
      speed_ = sim.speed();
      break;
    case Command::Kind::Write: {
      if (!plc_) break;
      Forced value{std::move(c.name), c.ref, std::move(c.bytes)};
      audited(c.writer, value, [&] {
        if (writeBytes(value, plc_->machine().memory())) plc_->inputsTouched();
      });
      plc::syncInputImage(plc_->module(), value.ref, plc_->machine().memory(), plc_->inputImage());
      auto same = std::ranges::find_if(forced_, [&](const Forced& f) { return iequalsAscii(f.name, value.name); });
      if (same != forced_.end()) forced_.erase(same);  // a new write replaces (or ends) a force
      if (c.force) forced_.push_back(std::move(value));
      break;
    }
    case Command::Kind::Release:
      if (c.name.empty()) forced_.clear();
      else std::erase_if(forced_, [&](const Forced& f) { return iequalsAscii(f.name, c.name); });
      break;
    case Command::Kind::Fault: {
      // Every command of the device fails with the code (errorAtCommand 0) until cleared with 0.
      plant::FaultPlan& plan = cell_->devices[c.device]->faults();
      plan.errorCode = c.code;
      plan.errorAtCommand = 0;
      break;
    }
    case Command::Kind::Reset: resetting_ = true; break;  // the run ends before this tick
  }
  if (c.kind == Command::Kind::Write || c.kind == Command::Kind::Release) {
    std::lock_guard lock(snapshotMutex_);
    snapshot_.forced.clear();
    for (const Forced& f : forced_) snapshot_.forced.push_back(f.name);
  }
}

template <class Write>
void LiveState::audited(const ExternalWriter& writer, const Forced& value, Write&& write) {
  if (!audit_) return write();
  const bc::Module& m = plc_->module();
  audit_->setVirtualTime(plc_->nextTickNs());  // the scan boundary it crosses, as the servers' writes
  const uint8_t bitMask = value.ref.bit >= 0 ? static_cast<uint8_t>(1u << value.ref.bit) : 0;
  audit_->beforeEdit(writer, {plc_->machine().memory(), m.staticSize}, 0, value.ref.address,
                     static_cast<uint32_t>(value.bytes.size()), bitMask);
  write();
  audit_->endEdits();
}

void LiveState::applyForces(plc::Runtime& plc) {
  bool touched = false;
  uint8_t* memory = plc.machine().memory();
  for (const Forced& f : forced_) {
    touched |= writeBytes(f, memory);
    plc::syncInputImage(plc.module(), f.ref, memory, plc.inputImage());
  }
  if (touched) plc.inputsTouched();
}

bool LiveState::writeBytes(const Forced& f, uint8_t* memory) {
  uint8_t* at = memory + f.ref.address;
  if (f.ref.bit >= 0) {
    const uint8_t mask = static_cast<uint8_t>(1u << f.ref.bit);
    const uint8_t next = static_cast<uint8_t>((*at & ~mask) | (f.bytes[0] & mask));
    bool changed = next != *at;
    *at = next;
    return changed;
  }
  bool changed = std::memcmp(at, f.bytes.data(), f.bytes.size()) != 0;
  std::memcpy(at, f.bytes.data(), f.bytes.size());
  return changed;
}

}  // namespace virtcom::hmi
