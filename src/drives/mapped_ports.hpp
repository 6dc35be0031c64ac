#pragma once
// A drive device with a `mapping:` (lib/mappings/*.yaml) exposes the UNIVERSAL_AXIS signals
// instead of its telegram words: Control_* ports in, Status_* and the mapping's Cfg_* constants
// out, so `wiring: MAIN.Axis1` connects the drive straight to a UNIVERSAL_AXIS instance. Every
// tick the Control_* values are packed into the output words in the mapping's byte order and
// decoded by the drive with the telegram's own order (a byte-order mistake shows up as on a real
// bus), and the reply words are unpacked into the Status_* ports. No allocation per tick.
//
// Per tick only what changed is converted (the PLC mostly holds its commands, and a moving drive
// changes a few reply words): unchanged Control_* ports leave the packed words as they are but
// for the master sign-of-life, unchanged reply words leave their Status_* values, and an
// unchanged value is written back to its port as the bus value it gave before. The results are
// those of converting everything every tick.
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
  void setFirstPort(size_t index);

  // Control_* port values -> the raw words the drive receives.
  void receive(const plant::Device& device, const TagBus& bus, RawWords& rx);
  // The drive's reply words -> Status_* ports; Cfg_* ports get their constants.
  void reply(const plant::Device& device, const RawWords& tx, TagBus& bus);

 private:
  // The In (Control_*) or the Out (Status_*, Cfg_*) ports as parallel arrays, so the per-tick
  // scans read only what they compare.
  struct PortList {
    std::vector<size_t> port;          // device port index
    std::vector<size_t> signal;        // index into values_
    std::vector<TagId> tag;            // the port's tag, once bound
    std::vector<uint64_t> raw;         // the tag's bus value last read (In) or written (Out)
    std::vector<uint64_t> valueBits;   // Out: the bits of the value that gave `raw`
    void add(size_t portIndex, AxisSignal s);
  };
  // The ports' tags: the cell binds them after construction, before the first tick.
  void bindTags(const plant::Device& device);
  // Reads the Control_* ports that changed into values_; false if none did.
  bool readChangedInputs(const TagBus& bus);

  std::shared_ptr<const MappingSpec> spec_;
  MappingRuntime runtime_;
  std::vector<Port> ports_;
  PortList in_, out_;
  bool bound_ = false, replied_ = false;
  AxisSignalValues values_{};
  RawWords toDrive_{}, fromDrive_{};  // in the mapping's byte order
};

}  // namespace virtcom::drives
