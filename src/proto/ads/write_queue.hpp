#pragma once
// Writes from ADS clients waiting for the next scan boundary. Bounded and allocation-free after
// construction, so the scan thread can drain it on its hot path.
#include <cstdint>
#include <span>
#include <vector>

#include "proto/ads/symbol_table.hpp"

namespace virtcom::proto::ads {

class WriteQueue {
 public:
  // Room for `capacityBytes` of written data (and as many edits).
  explicit WriteQueue(size_t capacityBytes);
  bool hasRoom(size_t dataBytes) const;
  // Precondition: hasRoom(data.size()). bitMask 0: the bytes replace [offset, offset + size);
  // else data is one byte and only the bits in bitMask of image[offset] take its (0 / non-0) value.
  void push(uint32_t offset, std::span<const uint8_t> data, uint8_t bitMask = 0);
  // Applies every edit in arrival order to `image` (edits outside it are skipped); the part of an
  // edit that falls into `mirror` is also applied to `mirrorImage` (index 0 = mirror.offset).
  void applyTo(std::span<uint8_t> image, ByteRange mirror = {}, std::span<uint8_t> mirrorImage = {}) const;
  void clear();
  bool empty() const { return edits_.empty(); }
  size_t size() const { return edits_.size(); }

 private:
  struct Edit {
    uint32_t offset = 0, size = 0, dataPos = 0;
    uint8_t bitMask = 0;
  };
  static void applyOne(const Edit& e, const uint8_t* data, std::span<uint8_t> image, uint32_t base);
  std::vector<Edit> edits_;
  std::vector<uint8_t> data_;
  size_t capacityBytes_;
};

}  // namespace virtcom::proto::ads
