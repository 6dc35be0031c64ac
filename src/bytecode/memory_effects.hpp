#pragma once
// What memory an instruction reads or writes, where a POU's accesses point (relative to its fp
// and this), and what a call of a POU may write. Shared by the compiler's load forwarding (which
// loads a call leaves valid) and the VM's quickener (which accesses cannot leave memory).
#include <cstdint>
#include <optional>
#include <vector>

#include "bytecode/module.hpp"

namespace virtcom::bc {

// The bytes an instruction reads or writes: `width` bytes at r[base] + offset, or at the absolute
// address `offset` (base unused). A bit access covers its byte (offset 0: C is the bit).
struct MemoryRange {
  bool absolute = false;
  uint16_t base = 0;
  uint32_t offset = 0;
  uint32_t width = 0;
};

// The range a load (LD_*, LD_BIT, LDA_*) reads; nullopt for every other instruction.
std::optional<MemoryRange> loadedRange(const Instr& ins);
// The range a store (ST_*, STK_*, ST_BIT, STA_*) or a standard FB (CALLFB: its instance) writes;
// nullopt for instructions that write no memory or more than one range they name (COPY, ENTER,
// CALL, CALLN, COVER: see writesBeyondRanges).
std::optional<MemoryRange> storedRange(const Instr& ins);
// True for the instructions whose memory writes storedRange does not describe.
bool writesBeyondRanges(Op op);
// The size of a standard FB's instance: what CALLFB reads and writes.
uint32_t nativeFbSize(NativeFb f);

// True if no instruction of POU `p` can change r0 or r1 of its window (no destination register
// below 2, no CALL or CALLN window starting below 2): fp and this keep their entry values.
bool basesReadOnly(const Module& m, const PouInfo& p);

// Where the base register of an access points: `reach` bytes or less past fp (base 0) or this
// (base 1), never before it.
struct Placed {
  uint16_t base;
  uint64_t reach;
};

// For each instruction of POU `p` (whose r0 and r1 nothing writes: basesReadOnly), where its B
// register (CALLFB: its A, the instance) points if it is fp, this, or an address computed from
// them in the same basic block: an array element (ADD of fp/this and an INDEX, at most
// IndexDesc::lastOffset past them), a member at a constant offset (ADDI of a non-negative
// constant), or both (a member of an element, an FB instance in an array).
std::vector<std::optional<Placed>> placedBases(const Module& m, const PouInfo& p);

// What a call of POU `p` may write in memory outside the stack above its caller's frames (its
// own frame and those of its callees, which the caller's fp lies below): only the first
// `reach` bytes past the this it is passed (0: nothing); nullopt when it may write anywhere else
// (a store through a pointer or to a global, COPY, CALL, CALLN, COVER) or its code is not there
// yet (codeSize 0: a POU still being compiled).
std::optional<uint64_t> thisWriteReach(const Module& m, const PouInfo& p);

}  // namespace virtcom::bc
