#pragma once
// A drive device with a `mapping:` (lib/mappings/*.yaml) exposes the UNIVERSAL_AXIS signals
// instead of its telegram words: Control_* ports in, Status_* and the mapping's Cfg_* constants
// out, so `wiring: MAIN.Axis1` connects the drive straight to a UNIVERSAL_AXIS instance. Every
// tick the Control_* values are packed into the output image in the mapping's byte order and
// decoded by the drive with the telegram's own order (a byte-order mistake shows up as on a real
// bus), and the reply image is unpacked into the Status_* ports. No allocation per tick.
#include <memory>
#include <vector>

#include "drives/axis_mapping.hpp"
#include "plant/device.hpp"

namespace virtcom::drives {

class MappedPorts {
 public:
  explicit MappedPorts(std::shared_ptr<const MappingSpec> spec);

  struct Port {
    AxisSignal signal;
    plant::PortDir dir;
  };
  // The ports, in the order the device must register them starting at `firstPort`.
  const std::vector<Port>& ports() const { return ports_; }
  void setFirstPort(size_t index) { firstPort_ = index; }

  // Control_* port values -> the raw words the drive receives.
  void receive(const plant::Device& device, const TagBus& bus, RawWords& rx);
  // The drive's reply words -> Status_* ports; Cfg_* ports get their constants.
  void reply(const plant::Device& device, const RawWords& tx, TagBus& bus);

 private:
  std::shared_ptr<const MappingSpec> spec_;
  MappingRuntime runtime_;
  std::vector<Port> ports_;
  size_t firstPort_ = 0;
  AxisSignalValues values_{};
  RawWords words_{};
  std::array<uint8_t, kMaxImageBytes> image_{};
};

}  // namespace virtcom::drives
