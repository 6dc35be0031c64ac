// MEMCPY/MEMMOVE, MEMSET and MEMCMP over the PLC's memory image: every range is checked
// against the image (and its null guard) before a byte moves.
#include <cstring>

#include "vm/natives.hpp"

namespace virtcom::vm {

using bc::FaultKind;

namespace {

bool inMemory(const NativeContext& c, uint64_t addr, uint64_t n) {
  return addr >= c.nullGuard && addr <= c.memorySize && n <= c.memorySize - addr;
}

}  // namespace

FaultKind native_MEM_COPY(uint64_t* a, const NativeContext& c) {
  const uint64_t dst = a[0], src = a[1], n = a[2];
  if (!inMemory(c, dst, n) || !inMemory(c, src, n)) return FaultKind::InvalidPointer;
  std::memmove(c.memory + dst, c.memory + src, n);
  return FaultKind::None;
}

FaultKind native_MEM_SET(uint64_t* a, const NativeContext& c) {
  const uint64_t dst = a[0], n = a[2];
  if (!inMemory(c, dst, n)) return FaultKind::InvalidPointer;
  std::memset(c.memory + dst, static_cast<int>(a[1] & 0xFF), n);
  return FaultKind::None;
}

FaultKind native_MEM_CMP(uint64_t* a, const NativeContext& c) {
  const uint64_t x = a[0], y = a[1], n = a[2];
  if (!inMemory(c, x, n) || !inMemory(c, y, n)) return FaultKind::InvalidPointer;
  const int order = n == 0 ? 0 : std::memcmp(c.memory + x, c.memory + y, n);
  a[0] = static_cast<uint64_t>(static_cast<int64_t>(order < 0 ? -1 : order > 0 ? 1 : 0));
  return FaultKind::None;
}

}  // namespace virtcom::vm
