#pragma once
// Allocates and fills the static part of the memory image at compile time.
#include <cstdint>
#include <cstring>
#include <vector>

#include "bytecode/module.hpp"

namespace virtcom::st {

class ImageBuilder {
 public:
  explicit ImageBuilder(std::vector<uint8_t>& image) : image_(image) {
    if (image_.size() < bc::Module::kNullGuard) image_.resize(bc::Module::kNullGuard, 0);
  }
  // Reserves `size` zeroed bytes aligned to `align` (clamped to 8); returns the address.
  uint32_t allocate(uint32_t size, uint32_t align) {
    if (align == 0) align = 1;
    if (align > 8) align = 8;
    size_t addr = (image_.size() + align - 1) / align * align;
    image_.resize(addr + size, 0);
    return static_cast<uint32_t>(addr);
  }
  uint8_t* at(uint32_t address) { return image_.data() + address; }
  uint32_t size() const { return static_cast<uint32_t>(image_.size()); }
  // Stores `bytes` (e.g. a string literal plus NUL) as read-only data; returns its address.
  uint32_t addData(const void* bytes, uint32_t size, uint32_t align = 1) {
    uint32_t addr = allocate(size, align);
    if (size) std::memcpy(image_.data() + addr, bytes, size);
    return addr;
  }

 private:
  std::vector<uint8_t>& image_;
};

}  // namespace virtcom::st
