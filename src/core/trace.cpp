#include "core/trace.hpp"

namespace virtcom {

const char* runEndName(RunEnd e) {
  switch (e) {
    case RunEnd::Completed: return "completed";
    case RunEnd::TimeLimit: return "time limit reached";
    case RunEnd::PlcFault: return "PLC fault";
    case RunEnd::DeviceError: return "device error";
    case RunEnd::Collision: return "collision";
    case RunEnd::Interrupted: return "interrupted";
  }
  return "?";
}

uint32_t Trace::internLabel(const std::string& label) {
  for (size_t i = 0; i < labels.size(); ++i)
    if (labels[i] == label) return static_cast<uint32_t>(i);
  labels.push_back(label);
  return static_cast<uint32_t>(labels.size() - 1);
}

uint32_t Trace::addDevice(std::string name, std::string type, std::string group) {
  devices.push_back({std::move(name), std::move(type), std::move(group)});
  totals.emplace_back();
  return static_cast<uint32_t>(devices.size() - 1);
}

void Trace::setWindow(size_t limit) {
  activities.setLimit(limit);
  cycles.setLimit(limit);
}

uint32_t Trace::beginActivity(uint32_t device, uint32_t label, int64_t nowNs) {
  ActivityRecord a;
  a.device = device;
  a.label = label;
  a.startNs = nowNs;
  return activities.push_back(a);
}

void Trace::endActivity(uint32_t activity, int64_t nowNs, double energyJ, int32_t errorCode) {
  ActivityRecord& a = activities[activity];
  a.endNs = nowNs;
  a.energyJ = energyJ;
  a.errorCode = errorCode;
}

void Trace::keepExternalWrite(const WriteRecord& record) {
  ++externalWrites[static_cast<size_t>(record.writer.protocol)];
  if (writeRecords.size() < kKeptWriteRecords) writeRecords.push_back(record);
}

}  // namespace virtcom
