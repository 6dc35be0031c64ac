#include "plant/device.hpp"

namespace virtcom::plant {

int Device::portIndex(const std::string& name) const {
  for (size_t i = 0; i < ports_.size(); ++i)
    if (ports_[i].name == name) return static_cast<int>(i);
  return -1;
}

size_t Device::addPort(std::string name, ElemType type, PortDir dir, std::string doc) {
  ports_.push_back({std::move(name), type, dir, std::move(doc)});
  tags_.push_back(kNoTag);
  return ports_.size() - 1;
}

void Device::prepare(World& world, Trace& trace) {
  (void)world;
  traceIndex_ = trace.addDevice(name_, type_, group_);
}

void Device::finish(int64_t endNs, Trace& trace) {
  (void)endNs;
  (void)trace;
}

}  // namespace virtcom::plant
