#pragma once
// Bounds-checked little-endian readers and writers for AMS/ADS frames (ADS is little endian on
// the wire: docs/ads.md, Wire reference: Byte order and strings); the OPC UA codec reads and
// writes through them too (OPC UA binary is little endian: docs/opcua.md).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace virtcom::proto::ads {

// Reads from a byte span; every read returns nullopt instead of running past the end.
class LittleEndianReader {
 public:
  explicit LittleEndianReader(std::span<const uint8_t> bytes) : bytes_(bytes) {}
  std::optional<uint8_t> u8() { return fixed<uint8_t>(); }
  std::optional<uint16_t> u16() { return fixed<uint16_t>(); }
  std::optional<uint32_t> u32() { return fixed<uint32_t>(); }
  std::optional<uint64_t> u64() { return fixed<uint64_t>(); }
  // The next n bytes, or nullopt if fewer remain.
  std::optional<std::span<const uint8_t>> bytes(size_t n) {
    if (remaining() < n) return std::nullopt;
    auto s = bytes_.subspan(pos_, n);
    pos_ += n;
    return s;
  }
  std::span<const uint8_t> rest() const { return bytes_.subspan(pos_); }
  size_t remaining() const { return bytes_.size() - pos_; }

 private:
  template <class T>
  std::optional<T> fixed() {
    if (remaining() < sizeof(T)) return std::nullopt;
    uint64_t v = 0;
    for (size_t i = 0; i < sizeof(T); ++i) v |= uint64_t{bytes_[pos_ + i]} << (8 * i);
    pos_ += sizeof(T);
    return static_cast<T>(v);
  }
  std::span<const uint8_t> bytes_;
  size_t pos_ = 0;
};

// Appends to a growing buffer (responses are built payload first; fixed-size fields that depend
// on what follows are patched with put32 once known). Allocates only when the buffer grows.
class LittleEndianWriter {
 public:
  explicit LittleEndianWriter(std::vector<uint8_t>& out) : out_(out) {}
  void u8(uint8_t v) { out_.push_back(v); }
  void u16(uint16_t v) { fixed(v, 2); }
  void u32(uint32_t v) { fixed(v, 4); }
  void u64(uint64_t v) { fixed(v, 8); }
  void bytes(std::span<const uint8_t> b) { out_.insert(out_.end(), b.begin(), b.end()); }
  void zeros(size_t n) { out_.insert(out_.end(), n, 0); }
  // The characters followed by one NUL.
  void cstring(std::string_view s) {
    out_.insert(out_.end(), s.begin(), s.end());
    out_.push_back(0);
  }
  size_t size() const { return out_.size(); }
  // Overwrites the u32 at `at` (an offset already written).
  void put32(size_t at, uint32_t v) {
    for (size_t i = 0; i < 4; ++i) out_[at + i] = static_cast<uint8_t>(v >> (8 * i));
  }

 private:
  void fixed(uint64_t v, size_t n) {
    for (size_t i = 0; i < n; ++i) out_.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
  std::vector<uint8_t>& out_;
};

}  // namespace virtcom::proto::ads
