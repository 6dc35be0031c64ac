#include "drives/telegram_device.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "plant/config_helpers.hpp"

namespace virtcom::drives {
namespace {


uint32_t rawFromTag(const TagBus& bus, TagId tag, WireType type) {
  if (type == WireType::F32) return rawFromReal(bus.getReal(tag));
  return rawFromInt(type, bus.getInt(tag));
}

void rawToTag(TagBus& bus, TagId tag, WireType type, uint32_t raw) {
  if (type == WireType::F32) bus.setReal(tag, realValue(raw));
  else bus.setInt(tag, signedValue(type, raw));
}

}  // namespace

TelegramDevice::TelegramDevice(std::string name, std::string type, DriveCommon common, MessageFamily family)
    : plant::Device(std::move(name), std::move(type)), common_(std::move(common)), family_(family) {
  if (common_.mapping) {
    mapped_.emplace(common_.mapping);
    mapped_->setFirstPort(ports().size());
    for (const MappedPorts::Port& p : mapped_->ports()) {
      const AxisSignalDef& s = axisSignal(p.signal);
      addPort(std::string(s.name), s.type, p.dir, std::string(s.doc));
    }
  } else {
    for (const WordDef& w : words(common_.telegram, Dir::ToDrive))
      addPort(std::string(w.name), elemType(w.type), plant::PortDir::In, std::string(w.doc));
    for (const WordDef& w : words(common_.telegram, Dir::FromDrive))
      addPort(std::string(w.name), elemType(w.type), plant::PortDir::Out, std::string(w.doc));
  }
  stepS_ = static_cast<double>(common_.stepNs) * 1e-9;
  const double travelPerLoadRev = common_.load.mmPerRev > 0 ? common_.load.mmPerRev : 1.0;
  travelPerRpmStep_ = stepS_ / 60.0 / common_.load.gearRatio * travelPerLoadRev;
  joulesPerNmRpmStep_ = kRadPerRpm * stepS_;
  rxCount_ = words(common_.telegram, Dir::ToDrive).size();
  txCount_ = words(common_.telegram, Dir::FromDrive).size();
  speedPort_ = addPort("speed", ElemType::Lreal, plant::PortDir::Out, "motor speed in rpm (simulation output)");
  torquePort_ = addPort("torque", ElemType::Lreal, plant::PortDir::Out, "motor torque in N*m (simulation output)");
  positionPort_ = addPort("position", ElemType::Lreal, plant::PortDir::Out,
                          "load position in mm (load `lead` set) or load revolutions (simulation output)");
}

void TelegramDevice::prepare(plant::World& world, Trace& trace) {
  Device::prepare(world, trace);
  trace_ = &trace;
  runLabel_ = trace.internLabel("Running");
}

void TelegramDevice::step(const plant::StepContext& ctx) {
  if (commLost(ctx.nowNs)) {
    exchange({}, ctx.nowNs);
  } else if (mapped_) {
    mapped_->receive(*this, ctx.bus, rx_);
    exchange(std::span<const uint32_t>(rx_.data(), rxCount_), ctx.nowNs);
  } else {
    const auto ws = words(common_.telegram, Dir::ToDrive);
    for (size_t i = 0; i < rxCount_; ++i) rx_[i] = rawFromTag(ctx.bus, tag(i), ws[i].type);
    exchange(std::span<const uint32_t>(rx_.data(), rxCount_), ctx.nowNs);
  }
  if (mapped_) {
    mapped_->reply(*this, tx_, ctx.bus);
  } else {
    const auto ws = words(common_.telegram, Dir::FromDrive);
    for (size_t i = 0; i < txCount_; ++i) rawToTag(ctx.bus, tag(rxCount_ + i), ws[i].type, tx_[i]);
  }
  ctx.bus.setReal(tag(speedPort_), speedRpm_);
  ctx.bus.setReal(tag(torquePort_), torqueNm_);
  ctx.bus.setReal(tag(positionPort_), loadPosition_);
  const bool running = std::abs(speedRpm_) >= 1.0;
  if (running && !running_) {
    runStartNs_ = ctx.nowNs;
    activityEnergyJ_ = energyJ_;
    activity_ = ctx.trace.beginActivity(traceIndex(), runLabel_, ctx.nowNs);
  } else if (!running && running_) {
    busyNs_ += ctx.nowNs - runStartNs_;
    ctx.trace.endActivity(activity_, ctx.nowNs, energyJ_ - activityEnergyJ_);
  }
  running_ = running;
}

void TelegramDevice::exchange(std::span<const uint32_t> rx, int64_t nowNs) {
  advanceTo(nowNs);
  applyInjections(nowNs);
  if (rx.empty()) onMissingFrame(nowNs);
  else onFrame(rx, nowNs);
  encode(tx_);
}

void TelegramDevice::advanceTo(int64_t nowNs) {
  while (lastNs_ + common_.stepNs <= nowNs) {
    integrate(stepS_);
    loadPosition_ += speedRpm_ * travelPerRpmStep_;
    energyJ_ += std::abs(torqueNm_ * speedRpm_) * joulesPerNmRpmStep_;
    lastNs_ += common_.stepNs;
  }
}

void TelegramDevice::applyInjections(int64_t nowNs) {
  for (Injection& inj : common_.injections) {
    if (!inj.raised) {
      if (nowNs < inj.atNs || std::abs(speedRpm_) < inj.minSpeedRpm) continue;
      inj.raised = true;
      inj.raisedNs = nowNs;
      raiseInjected(inj, nowNs);
    }
    if (!inj.causeGone && inj.durationNs >= 0 && nowNs >= inj.raisedNs + inj.durationNs) {
      inj.causeGone = true;
      clearInjected(inj, nowNs);
    }
  }
}

bool TelegramDevice::commLost(int64_t nowNs) const {
  for (const CommLossWindow& w : common_.commLoss)
    if (nowNs >= w.fromNs && nowNs < w.toNs) return true;
  return false;
}

int64_t TelegramDevice::nextEventNs() const {
  int64_t next = settled() ? INT64_MAX : lastNs_ + common_.stepNs;
  for (const Injection& inj : common_.injections) {
    if (!inj.raised) next = std::min(next, inj.atNs);
    else if (!inj.causeGone && inj.durationNs >= 0) next = std::min(next, inj.raisedNs + inj.durationNs);
  }
  for (const CommLossWindow& w : common_.commLoss) {
    if (w.fromNs > lastNs_) next = std::min(next, w.fromNs);
    else if (w.toNs > lastNs_) return 0;  // frames are missing: counted every tick
  }
  return next;
}

void TelegramDevice::noteFault(int64_t nowNs, const std::string& message) {
  if (trace_) trace_->faults.push_back({nowNs, name(), message});
}

void TelegramDevice::finish(int64_t endNs, Trace& trace) {
  DeviceTotals& t = trace.totals[traceIndex()];
  t.busyNs = busyNs_ + (running_ ? endNs - runStartNs_ : 0);
  t.energyJ = energyJ_;
}

void TelegramDevice::readFaults(ConfigReader& f) {
  if (const ConfigNode* list = f.child("inject")) {
    if (list->kind() != ConfigNode::Kind::List) {
      f.error(list->loc(), "'inject' must be a list such as [{code: F07900, at: 2 s, duration: 500 ms}]");
    } else {
      for (const ConfigNode& item : list->items()) {
        ConfigReader r(item, f.diags(), "fault injection");
        Injection inj;
        const std::string code = r.requireString("code");
        inj.atNs = plant::optDurationNs(r, "at", 0);
        const bool hasDuration = r.has("duration");
        if (hasDuration) inj.durationNs = plant::requireDurationNs(r, "duration");
        inj.minSpeedRpm = r.optNumber("at_speed_rpm", 0);
        if (!code.empty()) {
          if (auto message = parseInjectionCode(family_, code)) {
            inj.kind = message->kind;
            inj.number = message->number;
            inj.reaction = message->reaction;
          } else {
            r.error(item.find("code")->loc(), message.error());
          }
        }
        // Without a duration a fault's cause is gone at once (the first acknowledge clears it)
        // and an alarm stays for the rest of the run.
        if (!hasDuration) inj.durationNs = inj.kind == MessageKind::Fault ? 0 : -1;
        r.rejectUnknownKeys();
        common_.injections.push_back(inj);
      }
    }
  }
  if (const ConfigNode* list = f.child("comm_loss")) {
    if (list->kind() != ConfigNode::Kind::List) {
      f.error(list->loc(), "'comm_loss' must be a list such as [{at: 3 s, duration: 150 ms}]");
    } else {
      for (const ConfigNode& item : list->items()) {
        ConfigReader r(item, f.diags(), "communication loss");
        CommLossWindow w;
        w.fromNs = plant::requireDurationNs(r, "at");
        w.toNs = r.has("duration") ? w.fromNs + plant::requireDurationNs(r, "duration") : INT64_MAX;
        r.rejectUnknownKeys();
        common_.commLoss.push_back(w);
      }
    }
  }
}

}  // namespace virtcom::drives
