#include "proto/ads/write_queue.hpp"

#include <algorithm>

namespace virtcom::proto::ads {

WriteQueue::WriteQueue(size_t capacityBytes) : capacityBytes_(capacityBytes) {
  edits_.reserve(capacityBytes);
  data_.reserve(capacityBytes);
}

bool WriteQueue::hasRoom(size_t dataBytes) const {
  return edits_.size() < capacityBytes_ && dataBytes <= capacityBytes_ - data_.size();
}

void WriteQueue::push(uint32_t offset, std::span<const uint8_t> data, uint8_t bitMask) {
  edits_.push_back({offset, static_cast<uint32_t>(data.size()), static_cast<uint32_t>(data_.size()), bitMask, writer_});
  data_.insert(data_.end(), data.begin(), data.end());
}

void WriteQueue::applyOne(const Edit& e, const uint8_t* data, std::span<uint8_t> image, uint32_t base) {
  // [base, base + image.size()) is where `image` sits in the data area.
  uint64_t from = std::max<uint64_t>(e.offset, base);
  uint64_t to = std::min<uint64_t>(uint64_t{e.offset} + e.size, uint64_t{base} + image.size());
  for (uint64_t a = from; a < to; ++a) {
    uint8_t& target = image[a - base];
    uint8_t value = data[a - e.offset];
    target = e.bitMask ? static_cast<uint8_t>((target & ~e.bitMask) | (value ? e.bitMask : 0)) : value;
  }
}

void WriteQueue::applyTo(std::span<uint8_t> image, ByteRange mirror, std::span<uint8_t> mirrorImage, WriteObserver* audit) const {
  auto mirrored = mirrorImage.first(std::min<size_t>(mirror.size, mirrorImage.size()));
  for (const Edit& e : edits_) {
    if (audit) audit->beforeEdit(e.writer, image, 0, e.offset, e.size, e.bitMask);
    applyOne(e, data_.data() + e.dataPos, image, 0);
    if (!mirrored.empty()) applyOne(e, data_.data() + e.dataPos, mirrored, mirror.offset);
  }
  if (audit && !edits_.empty()) audit->endEdits();
}

void WriteQueue::clear() {
  edits_.clear();
  data_.clear();
}

}  // namespace virtcom::proto::ads
