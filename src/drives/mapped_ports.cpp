#include "drives/mapped_ports.hpp"

#include <bit>
#include <span>

namespace virtcom::drives {

MappedPorts::MappedPorts(std::shared_ptr<const MappingSpec> spec) : spec_(std::move(spec)), runtime_(*spec_) {
  for (const AxisSignalDef& s : axisSignals()) {
    const auto i = static_cast<size_t>(s.id);
    if (spec_->bound[i] && !spec_->unavailable[i])
      ports_.push_back({s.id, s.kind == SignalKind::Control ? plant::PortDir::In : plant::PortDir::Out});
  }
  for (const auto& [signal, value] : spec_->blockInputs) values_[static_cast<size_t>(signal)] = value;
  setFirstPort(0);
}

void MappedPorts::PortList::add(size_t portIndex, AxisSignal s) {
  port.push_back(portIndex);
  signal.push_back(static_cast<size_t>(s));
  tag.push_back(kNoTag);
  raw.push_back(0);
  valueBits.push_back(0);
}

void MappedPorts::setFirstPort(size_t index) {
  in_ = {};
  out_ = {};
  for (size_t i = 0; i < ports_.size(); ++i) (ports_[i].dir == plant::PortDir::In ? in_ : out_).add(index + i, ports_[i].signal);
}

void MappedPorts::bindTags(const plant::Device& device) {
  for (PortList* list : {&in_, &out_})
    for (size_t i = 0; i < list->port.size(); ++i) list->tag[i] = device.tag(list->port[i]);
  bound_ = true;
}

bool MappedPorts::readChangedInputs(const TagBus& bus) {
  // The PLC mostly holds its commands: one pass finds out whether anything changed at all.
  uint64_t difference = 0;
  for (size_t i = 0; i < in_.tag.size(); ++i) difference |= bus.raw(in_.tag[i]) ^ in_.raw[i];
  if (difference == 0) return false;
  // A port whose bus value has not changed still holds the value converted from it (a tag at 0
  // reads as 0 whatever its type, as values_ starts).
  for (size_t i = 0; i < in_.tag.size(); ++i) {
    const uint64_t raw = bus.raw(in_.tag[i]);
    if (raw == in_.raw[i]) continue;
    in_.raw[i] = raw;
    values_[in_.signal[i]] = bus.getNumber(in_.tag[i]);
  }
  return true;
}

void MappedPorts::receive(const plant::Device& device, const TagBus& bus, RawWords& rx) {
  if (!bound_) bindTags(device);
  if (readChangedInputs(bus) || !runtime_.repeatable()) {
    runtime_.pack(values_, toDrive_);
    runtime_.toDrive(toDrive_, rx, ~0u);
  } else {
    runtime_.toDrive(toDrive_, rx, runtime_.advanceSignOfLife(toDrive_));
  }
}

void MappedPorts::reply(const plant::Device& device, const RawWords& tx, TagBus& bus) {
  if (!bound_) bindTags(device);
  const uint32_t changed = runtime_.fromDrive(tx, fromDrive_);
  runtime_.unpack(fromDrive_, values_, replied_ ? changed : ~0u);
  // setRaw() of the value setNumber() stored before is what setNumber() of the same value does.
  // Spans and a local flag: the bus writes could alias the members, which would be reloaded
  // every iteration.
  const bool first = !replied_;
  const std::span<const TagId> tags(out_.tag);
  const std::span<const size_t> signals(out_.signal);
  const std::span<uint64_t> raws(out_.raw), valueBits(out_.valueBits);
  for (size_t i = 0; i < tags.size(); ++i) {
    const double v = values_[signals[i]];
    const auto bits = std::bit_cast<uint64_t>(v);
    if (!first && bits == valueBits[i]) {
      bus.setRaw(tags[i], raws[i]);
      continue;
    }
    bus.setNumber(tags[i], v);
    raws[i] = bus.raw(tags[i]);
    valueBits[i] = bits;
  }
  replied_ = true;
}

}  // namespace virtcom::drives
