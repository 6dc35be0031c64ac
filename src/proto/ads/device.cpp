#include "proto/ads/device.hpp"

#include <algorithm>

#include "proto/ads/byte_io.hpp"
#include "proto/ads/entries.hpp"
#include "proto/ads/index_group.hpp"

namespace virtcom::proto::ads {

namespace {

bool isBitGroup(uint32_t ig) {
  auto g = static_cast<IndexGroup>(ig);
  return g == IndexGroup::InputBits || g == IndexGroup::OutputBits || g == IndexGroup::MemoryBits;
}

// Appends `blob` if the client asked for at least all of it.
AdsError readBlob(std::span<const uint8_t> blob, uint32_t length, std::vector<uint8_t>& out) {
  if (length != kAnyLength && length < blob.size()) return AdsError::InvalidSize;
  out.insert(out.end(), blob.begin(), blob.end());
  return AdsError::None;
}

AdsError readU32(uint32_t value, uint32_t length, std::vector<uint8_t>& out) {
  if (length < 4) return AdsError::InvalidSize;
  LittleEndianWriter(out).u32(value);
  return AdsError::None;
}

}  // namespace

Device::Device(const SymbolTable& table, DeviceConfig config)
    : table_(table),
      config_(config),
      dataArea_{0, table.layout().dataSize},
      snapshot_(table.layout().dataSize, 0),
      pending_(config.writeQueueBytes),
      handles_(config.maxHandlesPerRoute, config.maxHandleRoutes) {
  for (const Symbol& s : table_.symbols()) appendSymbolEntry(symbolUpload_, s);
  for (const DataType& t : table_.types()) appendDataTypeEntry(typeUpload_, t);
  typeCount_ = static_cast<uint32_t>(table_.types().size());
}

const ByteRange* Device::areaOf(uint32_t ig) const {
  const MemoryLayout& l = table_.layout();
  switch (static_cast<IndexGroup>(ig)) {
    case IndexGroup::DataBytes: return &dataArea_;
    case IndexGroup::InputBytes:
    case IndexGroup::InputBits: return &l.inputs;
    case IndexGroup::OutputBytes:
    case IndexGroup::OutputBits: return &l.outputs;
    case IndexGroup::MemoryBytes:
    case IndexGroup::MemoryBits: return &l.memory;
    default: return nullptr;
  }
}

AdsError Device::read(uint32_t ig, uint32_t io, uint32_t length, std::vector<uint8_t>& out) const {
  const MemoryLayout& l = table_.layout();
  if (const ByteRange* area = areaOf(ig)) {
    if (isBitGroup(ig)) return readBits(*area, io, length, out);
    if (io > area->size) return AdsError::InvalidIndexOffset;
    if (length == kAnyLength) return AdsError::InvalidSize;
    // Past the area's end: what there is, with its actual length (docs/ads.md, Read lengths).
    length = std::min(length, area->size - io);
    auto bytes = std::span<const uint8_t>(snapshot_).subspan(area->offset + io, length);
    out.insert(out.end(), bytes.begin(), bytes.end());
    return AdsError::None;
  }
  switch (static_cast<IndexGroup>(ig)) {
    case IndexGroup::DataSize: return readU32(l.dataSize, length, out);
    case IndexGroup::InputSize: return readU32(l.inputs.size, length, out);
    case IndexGroup::OutputSize: return readU32(l.outputs.size, length, out);
    case IndexGroup::MemorySize: return readU32(l.memory.size, length, out);
    case IndexGroup::SymVersion:
      if (length < 1) return AdsError::InvalidSize;
      out.push_back(symbolVersion_);
      return AdsError::None;
    case IndexGroup::SymUpload: return readBlob(symbolUpload_, length, out);
    case IndexGroup::DataTypeUpload: return readBlob(typeUpload_, length, out);
    case IndexGroup::SymUploadInfo:
    case IndexGroup::SymUploadInfo2: {
      // v1 is 8 bytes; v2 24 and v3 64, whichever fits (ads-client accepts only 8, 24 or 64).
      size_t bytes = static_cast<IndexGroup>(ig) == IndexGroup::SymUploadInfo ? 8 : length >= 64 ? 64 : 24;
      if (length < bytes) return AdsError::InvalidSize;
      UploadInfo info{static_cast<uint32_t>(table_.symbols().size()), static_cast<uint32_t>(symbolUpload_.size()),
                      typeCount_, static_cast<uint32_t>(typeUpload_.size())};
      appendUploadInfo(out, info, bytes);
      return AdsError::None;
    }
    case IndexGroup::DeviceData: {
      if (io != 0) return AdsError::InvalidIndexOffset;
      if (length < 4) return AdsError::InvalidSize;
      LittleEndianWriter w(out);
      w.u16(adsState_);
      w.u16(0);
      return AdsError::None;
    }
    default: return AdsError::InvalidIndexGroup;
  }
}

AdsError Device::readBits(const ByteRange& area, uint32_t bitAddress, uint32_t length, std::vector<uint8_t>& out) const {
  // One byte (0 or 1) per bit, starting at bitAddress = byte * 8 + bit.
  if (bitAddress / 8 >= area.size) return AdsError::InvalidIndexOffset;
  if (length == 0 || length == kAnyLength) return AdsError::InvalidSize;
  length = static_cast<uint32_t>(std::min<uint64_t>(length, uint64_t{area.size} * 8 - bitAddress));
  for (uint64_t b = bitAddress; b < uint64_t{bitAddress} + length; ++b)
    out.push_back((snapshot_[area.offset + b / 8] >> (b % 8)) & 1);
  return AdsError::None;
}

AdsError Device::write(uint32_t ig, uint32_t io, std::span<const uint8_t> data) {
  const ByteRange* area = areaOf(ig);
  if (!area) {
    // A group the server knows but that takes no Write is "not supported"; others are unknown.
    return isKnownGroup(ig) ? AdsError::ServiceNotSupported : AdsError::InvalidIndexGroup;
  }
  if (config_.readOnly) return AdsError::AccessDenied;
  if (isBitGroup(ig)) return writeBits(*area, io, data);
  if (io > area->size) return AdsError::InvalidIndexOffset;
  if (data.size() > area->size - io) return AdsError::InvalidSize;
  const uint32_t offset = area->offset + io;
  if (table_.touchesReadOnly(offset, static_cast<uint32_t>(data.size()))) return AdsError::AccessDenied;
  if (!pending_.hasRoom(data.size())) return AdsError::DeviceBusy;
  pending_.push(offset, data);
  std::copy(data.begin(), data.end(), snapshot_.begin() + offset);
  return AdsError::None;
}

AdsError Device::writeBits(const ByteRange& area, uint32_t bitAddress, std::span<const uint8_t> data) {
  if (bitAddress / 8 >= area.size) return AdsError::InvalidIndexOffset;
  if (data.empty() || data.size() > uint64_t{area.size} * 8 - bitAddress) return AdsError::InvalidSize;
  for (uint64_t b = bitAddress; b < bitAddress + data.size(); ++b)
    if (table_.touchesReadOnly(static_cast<uint32_t>(area.offset + b / 8), 1)) return AdsError::AccessDenied;
  if (!pending_.hasRoom(data.size())) return AdsError::DeviceBusy;
  for (size_t i = 0; i < data.size(); ++i) {
    const uint64_t b = bitAddress + i;
    const auto offset = static_cast<uint32_t>(area.offset + b / 8);
    const auto mask = static_cast<uint8_t>(1u << (b % 8));
    pending_.push(offset, data.subspan(i, 1), mask);
    snapshot_[offset] = static_cast<uint8_t>(data[i] ? snapshot_[offset] | mask : snapshot_[offset] & ~mask);
  }
  return AdsError::None;
}

AdsError Device::requestState(uint16_t adsState, const ExternalWriter& writer) {
  if (config_.readOnly) return AdsError::AccessDenied;
  if (adsState != kAdsStateRun && adsState != kAdsStateStop) return AdsError::ServiceNotSupported;
  requestedState_ = StateRequest{adsState, writer};
  adsState_ = adsState;
  return AdsError::None;
}

std::optional<StateRequest> Device::takeStateRequest() {
  auto r = requestedState_;
  requestedState_.reset();
  return r;
}

void Device::publish(std::span<const uint8_t> image, uint16_t adsState) {
  std::copy_n(image.begin(), std::min(image.size(), snapshot_.size()), snapshot_.begin());
  // Writes not yet taken by the scan stay visible, so a client reads back what it wrote.
  pending_.applyTo(snapshot_);
  if (!requestedState_) adsState_ = adsState;
}

uint16_t Device::assignPort() {
  uint16_t p = nextPort_;
  nextPort_ = nextPort_ == 65535 ? 30000 : static_cast<uint16_t>(nextPort_ + 1);
  return p;
}

}  // namespace virtcom::proto::ads
