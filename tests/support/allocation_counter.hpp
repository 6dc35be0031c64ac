#pragma once
// Counts heap allocations (every form of global operator new) made while an AllocationCounter is
// alive, to prove a per-tick path allocates nothing (STYLE rule 7). The replacements live in
// allocation_counter.cpp; link the `test_allocation_counter` object library into the test binary.
#include <cstddef>

namespace virtcom::test {

class AllocationCounter {
 public:
  AllocationCounter();
  ~AllocationCounter();
  AllocationCounter(const AllocationCounter&) = delete;
  AllocationCounter& operator=(const AllocationCounter&) = delete;
  // Allocations since construction.
  size_t count() const;
};

}  // namespace virtcom::test
