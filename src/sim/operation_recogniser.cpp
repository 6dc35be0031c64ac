#include "sim/operation_recogniser.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "plant/conveyor.hpp"
#include "plant/sequenced_device.hpp"

namespace virtcom::sim {

namespace {

// Index of `name` in `names`, or -1 (load time only).
int64_t indexOf(const std::vector<std::string>& names, const std::string& name) {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<int64_t>(i);
  return -1;
}

std::vector<std::string> deviceNames(const Trace& t) {
  std::vector<std::string> names;
  for (const auto& d : t.devices) names.push_back(d.name);
  return names;
}

}  // namespace

DurationModel::DurationModel(const Trace& simulated, const Trace& watched) : labels_(watched.labels.size()) {
  expected_.assign(watched.devices.size() * labels_, Range{});
  const std::vector<std::string> watchedDevices = deviceNames(watched);
  for (const ActivityRecord& a : simulated.activities) {
    if (a.endNs < 0 || a.errorCode != 0) continue;
    int64_t device = indexOf(watchedDevices, simulated.devices[a.device].name);
    int64_t label = indexOf(watched.labels, simulated.labels[a.label]);
    if (device < 0 || label < 0) continue;
    Range& r = expected_[static_cast<size_t>(device) * labels_ + static_cast<size_t>(label)];
    const int64_t ns = a.endNs - a.startNs;
    r.minNs = r.known() ? std::min(r.minNs, ns) : ns;
    r.maxNs = std::max(r.maxNs, ns);
  }
  if (simulated.cyclesCompleted > 0) cycleNs_ = simulated.cycleEndNs - simulated.cycleStartNs;
}

DurationModel::Range DurationModel::expected(uint32_t device, uint32_t label) const {
  size_t at = static_cast<size_t>(device) * labels_ + label;
  return label < labels_ && at < expected_.size() ? expected_[at] : Range{};
}

double DurationModel::Range::deviation(int64_t actualNs) const {
  if (!known()) return 0;
  if (actualNs > maxNs) return maxNs == 0 ? INFINITY : static_cast<double>(actualNs - maxNs) / static_cast<double>(maxNs);
  if (actualNs < minNs) return static_cast<double>(actualNs - minNs) / static_cast<double>(minNs);
  return 0;
}

OperationRecogniser::OperationRecogniser(const std::vector<std::unique_ptr<plant::Device>>& devices, Trace& trace,
                                         const Trace* model, double threshold)
    : trace_(trace), model_(model ? DurationModel(*model, trace) : DurationModel()), threshold_(threshold) {
  using SD = plant::SequencedDevice;
  for (const auto& d : devices) {
    Watched w;
    w.device = d.get();
    w.traceDevice = d->traceIndex();
    if (dynamic_cast<const SD*>(d.get())) {
      w.command = d->tag(SD::kCommandPort);
      w.execute = d->tag(SD::kExecutePort);
      w.done = d->tag(SD::kDonePort);
      w.error = d->tag(SD::kErrorPort);
      w.busy = d->tag(SD::kBusyPort);
    } else if (auto* c = dynamic_cast<const plant::Conveyor*>(d.get())) {
      w.conveyor = true;
      w.execute = c->tag(c->runPort());
    } else {
      continue;  // sensors and drives have no operations of their own here
    }
    watched_.push_back(w);
  }
  statIndex_.assign(trace.devices.size() * trace.labels.size(), -1);
  stats_.reserve(256);
}

void OperationRecogniser::observe(const TagBus& bus, int64_t nowNs) {
  for (Watched& w : watched_) {
    if (w.conveyor) observeConveyor(w, bus, nowNs);
    else observeHandshake(w, bus, nowNs);
  }
}

void OperationRecogniser::observeHandshake(Watched& w, const TagBus& bus, int64_t nowNs) {
  const bool execute = bus.getBool(w.execute), done = bus.getBool(w.done), busy = bus.getBool(w.busy);
  const int32_t error = static_cast<int32_t>(bus.getInt(w.error));
  const bool joining = w.phase == Phase::Unseen;
  if (joining) {
    // Joining a running plant: a command already finished is its past, one running is recorded
    // from now on (and not compared: its start is not known).
    w.phase = execute && (done || error != 0) ? Phase::WaitDrop : Phase::Idle;
  }
  if (w.phase == Phase::Idle && execute) {
    const auto* device = static_cast<const plant::SequencedDevice*>(w.device);
    begin(w, device->operationLabel(bus.getNumber(w.command)), nowNs, joining);
  }
  if (w.phase == Phase::Running) {
    w.sawBusy |= busy;
    if (done || error != 0 || (w.sawBusy && !busy)) end(w, nowNs, error);
  }
  if (w.phase == Phase::WaitDrop && !execute && !done && error == 0) w.phase = Phase::Idle;
}

void OperationRecogniser::observeConveyor(Watched& w, const TagBus& bus, int64_t nowNs) {
  const bool run = bus.getBool(w.execute);
  const bool joining = w.phase == Phase::Unseen;
  if (joining || w.phase == Phase::WaitDrop) w.phase = Phase::Idle;
  const auto* conveyor = static_cast<const plant::Conveyor*>(w.device);
  if (w.phase == Phase::Idle && run) {
    begin(w, conveyor->runningLabel(), nowNs, joining);
  }
  else if (w.phase == Phase::Running && !run) end(w, nowNs, 0);
}

void OperationRecogniser::begin(Watched& w, uint32_t label, int64_t nowNs, bool joined) {
  w.activity = trace_.beginActivity(w.traceDevice, label, nowNs);
  w.phase = Phase::Running;
  w.sawBusy = false;
  w.joined = joined;
}

void OperationRecogniser::end(Watched& w, int64_t nowNs, int32_t error) {
  trace_.endActivity(w.activity, nowNs, 0, error);
  w.phase = Phase::WaitDrop;
  if (error == 0 && !w.joined) compare(w, trace_.activities[w.activity]);
}

void OperationRecogniser::compare(const Watched& w, const ActivityRecord& a) {
  size_t at = static_cast<size_t>(a.device) * trace_.labels.size() + a.label;
  if (statIndex_[at] < 0) {
    statIndex_[at] = static_cast<int32_t>(stats_.size());
    stats_.push_back({a.device, a.label, 0, 0, model_.expected(a.device, a.label), 0, 0});
  }
  OperationStats& s = stats_[static_cast<size_t>(statIndex_[at])];
  const int64_t actualNs = a.endNs - a.startNs;
  ++s.count;
  s.totalNs += actualNs;
  const double deviation = s.expected.deviation(actualNs);
  if (std::abs(deviation) > std::abs(s.worstDeviation)) s.worstDeviation = deviation;
  if (std::abs(deviation) <= threshold_) return;
  ++s.alerts;
  char model[64], text[192];
  if (s.expected.minNs == s.expected.maxNs) std::snprintf(model, sizeof model, "%.3f s", s.expected.maxNs / 1e9);
  else std::snprintf(model, sizeof model, "%.3f to %.3f s", s.expected.minNs / 1e9, s.expected.maxNs / 1e9);
  std::snprintf(text, sizeof text, "%s took %.3f s, the model %s (%+.0f %%)", trace_.labels[a.label].c_str(), actualNs / 1e9, model,
                deviation * 100);
  trace_.faults.push_back({a.endNs, w.device->name(), text});
}

}  // namespace virtcom::sim
