#pragma once
// Load-time checks of a program image: after verifyModule accepts a module, the interpreter
// can run it without ever indexing outside code, registers, constants, POUs or natives.
#include <cstdint>
#include <string>

#include "bytecode/module.hpp"

namespace virtcom::bc {

// What an instruction's operand field means (shared by the verifier and the disassembler).
enum class Operand : uint8_t {
  None,
  Reg,       // a register of the current window
  Imm,       // an unsigned 16-bit immediate (offsets)
  SImm,      // a signed 16-bit immediate (ADDI, the K comparisons, the value of STK_*)
  BitIndex,  // 0..7 (LD_BIT / ST_BIT)
  BitCount,  // 1..64 (SEXT / ZEXT)
  Divisor,   // 1..65535 (DIVK / MODK)
  Index,     // an index into Module::indexes (INDEX)
  Branch,    // a signed 16-bit jump offset whose target lies inside the POU (fused compare-and-branch)
};
// Counter: the address of one of Module::coverage's counters (COVER).
enum class WideOperand : uint8_t { None, SImm, Imm, Const, Abs, Pou, Native, NativeFb, Jump, Fault, Counter };

struct OperandRoles {
  Operand a = Operand::None, b = Operand::None, c = Operand::None;
  WideOperand bx = WideOperand::None;  // for ABx / AsBx formats
  uint8_t width = 0;                   // access width in bytes of absolute loads/stores
};
OperandRoles operandRoles(Op op);
// True when `op` only writes its register A (a load, an arithmetic result, ENTER); false when it
// reads A (stores, branches, CALL, CALLN, CALLFB, COPY) or A is no register.
bool writesOnlyA(Op op);

// Checks the whole module: POU code ranges, frame templates, every instruction's operands
// (registers inside the window, constant/POU/native indices, absolute addresses inside
// [kNullGuard, staticSize), jump targets inside the POU (also of the fused branches), last instruction of a POU is RET, JMP
// or TRAP), line table, types, symbols, programs, tasks and process areas.
// Returns "" if the module is fine, else the first problem, e.g.
// "pou 'MAIN' pc 12: register 40 outside window of 16". Allocates only for the message.
std::string verifyModule(const Module& m);

}  // namespace virtcom::bc
