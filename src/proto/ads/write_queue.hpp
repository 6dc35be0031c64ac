#pragma once
// Writes from ADS (and OPC UA) clients waiting for the next scan boundary, each with the client
// that made it (setWriter, before a request is answered). Bounded and allocation-free after
// construction, so the scan thread can drain it on its hot path.
#include <cstdint>
#include <span>
#include <vector>

#include "core/external_write.hpp"
#include "proto/ads/symbol_table.hpp"

namespace virtcom::proto::ads {

class WriteQueue {
 public:
  // Room for `capacityBytes` of written data (and as many edits).
  explicit WriteQueue(size_t capacityBytes);
  bool hasRoom(size_t dataBytes) const;
  void setWriter(const ExternalWriter& w) { writer_ = w; }
  // Precondition: hasRoom(data.size()). bitMask 0: the bytes replace [offset, offset + size);
  // else data is one byte and only the bits in bitMask of image[offset] take its (0 / non-0) value.
  void push(uint32_t offset, std::span<const uint8_t> data, uint8_t bitMask = 0);
  // Applies every edit in arrival order to `image` (edits outside it are skipped); the part of an
  // edit that falls into `mirror` is also applied to `mirrorImage` (index 0 = mirror.offset).
  // Each edit is reported to `audit` (if given) before it lands in `image` (PLC address 0).
  void applyTo(std::span<uint8_t> image, ByteRange mirror = {}, std::span<uint8_t> mirrorImage = {},
               WriteObserver* audit = nullptr) const;
  void clear();
  bool empty() const { return edits_.empty(); }
  size_t size() const { return edits_.size(); }

 private:
  struct Edit {
    uint32_t offset = 0, size = 0, dataPos = 0;
    uint8_t bitMask = 0;
    ExternalWriter writer;
  };
  static void applyOne(const Edit& e, const uint8_t* data, std::span<uint8_t> image, uint32_t base);
  std::vector<Edit> edits_;
  std::vector<uint8_t> data_;
  size_t capacityBytes_;
  ExternalWriter writer_;
};

}  // namespace virtcom::proto::ads
