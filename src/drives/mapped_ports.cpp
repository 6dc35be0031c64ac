#include "drives/mapped_ports.hpp"

namespace virtcom::drives {

MappedPorts::MappedPorts(std::shared_ptr<const MappingSpec> spec) : spec_(std::move(spec)), runtime_(*spec_) {
  for (const AxisSignalDef& s : axisSignals()) {
    const auto i = static_cast<size_t>(s.id);
    if (spec_->bound[i] && !spec_->unavailable[i])
      ports_.push_back({s.id, s.kind == SignalKind::Control ? plant::PortDir::In : plant::PortDir::Out});
  }
  for (const auto& [signal, value] : spec_->blockInputs) values_[static_cast<size_t>(signal)] = value;
}

void MappedPorts::receive(const plant::Device& device, const TagBus& bus, RawWords& rx) {
  for (size_t i = 0; i < ports_.size(); ++i)
    if (ports_[i].dir == plant::PortDir::In)
      values_[static_cast<size_t>(ports_[i].signal)] = bus.getNumber(device.tag(firstPort_ + i));
  runtime_.pack(values_, words_);
  runtime_.toWire(words_, image_);
  decode(spec_->telegram, Dir::ToDrive, image_, rx);
}

void MappedPorts::reply(const plant::Device& device, const RawWords& tx, TagBus& bus) {
  encode(spec_->telegram, Dir::FromDrive, tx, image_);
  runtime_.fromWire(image_, words_);
  runtime_.unpack(words_, values_);
  for (size_t i = 0; i < ports_.size(); ++i)
    if (ports_[i].dir == plant::PortDir::Out)
      bus.setNumber(device.tag(firstPort_ + i), values_[static_cast<size_t>(ports_[i].signal)]);
}

}  // namespace virtcom::drives
