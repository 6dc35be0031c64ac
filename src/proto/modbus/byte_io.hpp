#pragma once
// Bounds-checked big-endian readers and writers for Modbus frames (Modbus is big endian on the
// wire: MODBUS Application Protocol V1.1b3 section 4.2; the PLC image is little endian).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <span>

namespace virtcom::proto::modbus {

// Reads from a byte span; every read returns nullopt instead of running past the end.
class BigEndianReader {
 public:
  explicit BigEndianReader(std::span<const uint8_t> bytes) : bytes_(bytes) {}
  std::optional<uint8_t> u8() {
    if (remaining() < 1) return std::nullopt;
    return bytes_[pos_++];
  }
  std::optional<uint16_t> u16() {
    if (remaining() < 2) return std::nullopt;
    uint16_t v = static_cast<uint16_t>((bytes_[pos_] << 8) | bytes_[pos_ + 1]);
    pos_ += 2;
    return v;
  }
  // The next n bytes, or nullopt if fewer remain.
  std::optional<std::span<const uint8_t>> bytes(size_t n) {
    if (remaining() < n) return std::nullopt;
    auto s = bytes_.subspan(pos_, n);
    pos_ += n;
    return s;
  }
  size_t remaining() const { return bytes_.size() - pos_; }

 private:
  std::span<const uint8_t> bytes_;
  size_t pos_ = 0;
};

// Appends to a fixed buffer. Callers size their output from validated quantities, so running
// past the end is a broken invariant: it aborts with file:line rather than corrupting memory.
class BigEndianWriter {
 public:
  explicit BigEndianWriter(std::span<uint8_t> out) : out_(out) {}
  void u8(uint8_t v) {
    need(1);
    out_[pos_++] = v;
  }
  void u16(uint16_t v) {
    need(2);
    out_[pos_++] = static_cast<uint8_t>(v >> 8);
    out_[pos_++] = static_cast<uint8_t>(v & 0xff);
  }
  size_t size() const { return pos_; }

 private:
  void need(size_t n) const {
    if (out_.size() - pos_ < n) {
      std::fprintf(stderr, "%s:%d: BigEndianWriter overflow\n", __FILE__, __LINE__);
      std::abort();
    }
  }
  std::span<uint8_t> out_;
  size_t pos_ = 0;
};

}  // namespace virtcom::proto::modbus
