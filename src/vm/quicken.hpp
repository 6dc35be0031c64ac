#pragma once
// Load-time specialisation of a verified module's code for the interpreter ("quickening"):
// loads and stores relative to a POU's frame (r0) or instance (r1), or to an address computed
// from them in the same basic block (an array element, a member: bc::placedBases),
// that cannot leave memory once the POU's entry has checked fp and this, so their handlers skip
// checkedAddress; and the specialisations of VIRTCOM_VM_SPECIAL_OPS below.
//
// Why it is exact: a POU is quickened only if none of its instructions writes r0 or r1 (no
// destination register below 2, no CALL or CALLN window starting below 2), so fp and this keep
// their entry values for the whole activation. Its quickened accesses reach at most `extent`
// bytes past their base (the largest offset + width among them). On entry (Machine::run, CALL)
// the interpreter checks guard <= base <= memorySize - extent for both bases; then every such
// access lies inside [guard, memorySize) and checkedAddress would pass. If the check fails,
// that activation runs the module's own code, whose checked handlers fault exactly as before.
#include <cstdint>
#include <vector>

#include "bytecode/module.hpp"

namespace virtcom::vm {

// The quickened opcodes: same operands and meaning as the bytecode opcode of the same name.
#define VIRTCOM_VM_QUICK_OPS(Q)                                                                       \
  Q(LD_I8) Q(LD_U8) Q(LD_I16) Q(LD_U16) Q(LD_I32) Q(LD_U32) Q(LD_64) Q(LD_F32) Q(LD_BIT) Q(ST_8)      \
  Q(ST_16) Q(ST_32) Q(ST_64) Q(ST_F32) Q(ST_BIT) Q(STK_8) Q(STK_16) Q(STK_32) Q(STK_64)

// Interpreter-only specialisations, exact like the quickened accesses:
// - SEXT/ZEXT of 8, 16 or 32 bits (the widths of the IEC integers): one x86 extension instead
//   of shifts by a variable count. In every POU.
// - FOR_NEXT_I16/_I32: the end of a FOR loop over an INT/DINT variable as code generation emits
//   it, `ADDI a, a, k; ST_w a, base, off; LD_Iw a, base, off; JLE_I x, y, target` with base r0 or
//   r1 (quickened), in one dispatch instead of four. It replaces the ADDI only: the three others
//   stay in place, so a jump to one of them runs it on its own. In quickened POUs.
// - INDEX_ADD: an INDEX followed by an ADD (how an array element's address is computed: the
//   offset, then base + offset), both run in one dispatch; the ADD stays for jumps to it.
// - ENTER0: the ENTER of a POU without a frame (most function blocks): no copy of a template.
// - ENTER0_CALL: such an ENTER followed by a MOV and a CALL (how a user FB is called: its fp,
//   its this, the call) in one dispatch; the MOV and the CALL stay for jumps to them, and a
//   fault of the CALL is reported at its own pc.
// - CALLFB: a standard FB whose instance is placed like a quickened access (an element of an
//   array of TONs), called without checkedAddress. In quickened POUs.
#define VIRTCOM_VM_SPECIAL_OPS(S)                                                                  \
  S(SEXT8) S(SEXT16) S(SEXT32) S(ZEXT8) S(ZEXT16) S(ZEXT32) S(FOR_NEXT_I16) S(FOR_NEXT_I32) S(INDEX_ADD) \
  S(ENTER0) S(ENTER0_CALL) S(CALLFB)

// Interpreter-only opcode numbers, right after the bytecode's (bc::Op::Count_).
enum class QuickOp : uint8_t {
#define Q(name) name,
  VIRTCOM_VM_QUICK_OPS(Q) VIRTCOM_VM_SPECIAL_OPS(Q)
#undef Q
  Count_
};
static_assert(static_cast<unsigned>(bc::Op::Count_) + static_cast<unsigned>(QuickOp::Count_) <= 256);

constexpr bc::Op quickOpcode(QuickOp q) {
  return static_cast<bc::Op>(static_cast<unsigned>(bc::Op::Count_) + static_cast<unsigned>(q));
}

// What a call of one POU needs, in one 32-byte entry: its entry condition, (fp - lo) <= fpSpan
// and (this - lo) <= thisSpan, unsigned (so a base below lo wraps to a huge value and fails;
// always true for a POU without quickened accesses), and, copied from bc::PouInfo, where its
// code starts and its register window.
struct PouEntry {
  uint64_t lo = 0;
  uint64_t fpSpan = UINT64_MAX;
  uint64_t thisSpan = UINT64_MAX;
  uint32_t codeStart = 0;
  uint32_t numRegs = 0;
  bool admits(uint64_t fp, uint64_t self) const { return fp - lo <= fpSpan && self - lo <= thisSpan; }
};

struct QuickCode {
  std::vector<bc::Instr> code;   // the module's code with quickened opcodes, same pcs
  std::vector<PouEntry> entry;   // one per POU
};

// `m` must have passed bc::verifyModule; `memorySize` is the machine's (m.memorySize()).
QuickCode quicken(const bc::Module& m, uint64_t memorySize);

}  // namespace virtcom::vm
