#include "sim/operation_recogniser.hpp"

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
  std::vector<int64_t> sum(watched.devices.size() * labels_, 0);
  std::vector<uint32_t> count(sum.size(), 0);
  const std::vector<std::string> watchedDevices = deviceNames(watched);
  for (const ActivityRecord& a : simulated.activities) {
    if (a.endNs < 0 || a.errorCode != 0) continue;
    int64_t device = indexOf(watchedDevices, simulated.devices[a.device].name);
    int64_t label = indexOf(watched.labels, simulated.labels[a.label]);
    if (device < 0 || label < 0) continue;
    size_t at = static_cast<size_t>(device) * labels_ + static_cast<size_t>(label);
    sum[at] += a.endNs - a.startNs;
    ++count[at];
  }
  expectedNs_.assign(sum.size(), -1);
  for (size_t i = 0; i < sum.size(); ++i)
    if (count[i] > 0) expectedNs_[i] = sum[i] / count[i];
  if (simulated.cyclesCompleted > 0) cycleNs_ = simulated.cycleEndNs - simulated.cycleStartNs;
}

int64_t DurationModel::expectedNs(uint32_t device, uint32_t label) const {
  size_t at = static_cast<size_t>(device) * labels_ + label;
  return label < labels_ && at < expectedNs_.size() ? expectedNs_[at] : -1;
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
  if (w.phase == Phase::Unseen) {
    // Joining a running plant: a command already finished is its past, one running is recorded
    // from now on.
    w.phase = execute && (done || error != 0) ? Phase::WaitDrop : Phase::Idle;
  }
  if (w.phase == Phase::Idle && execute) {
    const auto* device = static_cast<const plant::SequencedDevice*>(w.device);
    begin(w, device->operationLabel(bus.getNumber(w.command)), nowNs);
  }
  if (w.phase == Phase::Running) {
    w.sawBusy |= busy;
    if (done || error != 0 || (w.sawBusy && !busy)) end(w, nowNs, error);
  }
  if (w.phase == Phase::WaitDrop && !execute && !done && error == 0) w.phase = Phase::Idle;
}

void OperationRecogniser::observeConveyor(Watched& w, const TagBus& bus, int64_t nowNs) {
  const bool run = bus.getBool(w.execute);
  if (w.phase == Phase::Unseen || w.phase == Phase::WaitDrop) w.phase = Phase::Idle;
  const auto* conveyor = static_cast<const plant::Conveyor*>(w.device);
  if (w.phase == Phase::Idle && run) begin(w, conveyor->runningLabel(), nowNs);
  else if (w.phase == Phase::Running && !run) end(w, nowNs, 0);
}

void OperationRecogniser::begin(Watched& w, uint32_t label, int64_t nowNs) {
  w.activity = trace_.beginActivity(w.traceDevice, label, nowNs);
  w.phase = Phase::Running;
  w.sawBusy = false;
}

void OperationRecogniser::end(Watched& w, int64_t nowNs, int32_t error) {
  trace_.endActivity(w.activity, nowNs, 0, error);
  w.phase = Phase::WaitDrop;
  if (error == 0) compare(w, trace_.activities[w.activity]);
}

void OperationRecogniser::compare(const Watched& w, const ActivityRecord& a) {
  size_t at = static_cast<size_t>(a.device) * trace_.labels.size() + a.label;
  if (statIndex_[at] < 0) {
    statIndex_[at] = static_cast<int32_t>(stats_.size());
    stats_.push_back({a.device, a.label, 0, 0, model_.expectedNs(a.device, a.label), 0, 0});
  }
  OperationStats& s = stats_[static_cast<size_t>(statIndex_[at])];
  const int64_t actualNs = a.endNs - a.startNs;
  ++s.count;
  s.totalNs += actualNs;
  if (s.expectedNs <= 0) return;
  const double deviation = static_cast<double>(actualNs - s.expectedNs) / static_cast<double>(s.expectedNs);
  if (std::abs(deviation) > std::abs(s.worstDeviation)) s.worstDeviation = deviation;
  if (std::abs(deviation) <= threshold_) return;
  ++s.alerts;
  char text[160];
  std::snprintf(text, sizeof text, "%s took %.3f s, the model %.3f s (%+.0f %%)", trace_.labels[a.label].c_str(), actualNs / 1e9,
                s.expectedNs / 1e9, deviation * 100);
  trace_.faults.push_back({a.endNs, w.device->name(), text});
}

}  // namespace virtcom::sim
