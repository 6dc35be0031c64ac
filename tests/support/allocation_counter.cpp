#include "allocation_counter.hpp"

#include <cstdlib>
#include <new>

namespace {
bool gCounting = false;
size_t gAllocations = 0;

void* countedAlloc(size_t size) noexcept {
  if (gCounting) ++gAllocations;
  return std::malloc(size ? size : 1);
}
}  // namespace

// Every non-aligned form is replaced so allocation and release always pair up (ASan checks).
void* operator new(size_t size) {
  if (void* p = countedAlloc(size)) return p;
  throw std::bad_alloc();
}
void* operator new[](size_t size) {
  if (void* p = countedAlloc(size)) return p;
  throw std::bad_alloc();
}
void* operator new(size_t size, const std::nothrow_t&) noexcept { return countedAlloc(size); }
void* operator new[](size_t size, const std::nothrow_t&) noexcept { return countedAlloc(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, size_t) noexcept { std::free(p); }
void operator delete[](void* p, size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

namespace virtcom::test {

AllocationCounter::AllocationCounter() {
  gAllocations = 0;
  gCounting = true;
}
AllocationCounter::~AllocationCounter() { gCounting = false; }
size_t AllocationCounter::count() const { return gAllocations; }

}  // namespace virtcom::test
