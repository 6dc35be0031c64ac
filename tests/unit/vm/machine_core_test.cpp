// Dispatch loop: every opcode group on hand-assembled code.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <vector>

#include "bytecode/verifier.hpp"
#include "test_module_builder.hpp"
#include "vm/machine.hpp"

namespace virtcom {
namespace {

using test::abc;
using test::abx;
using test::asbx;
using test::ModuleBuilder;
using bc::Op;

constexpr uint32_t kOut = 16;  // results are stored here

// Runs `prog` as MAIN (8 registers) followed by STA_64 result -> kOut; returns mem[kOut].
uint64_t eval(std::vector<bc::Instr> prog, uint16_t result, std::vector<uint64_t> constants = {}) {
  ModuleBuilder b;
  for (auto k : constants) b.constant(k);
  b.beginPou("MAIN", 8);
  for (auto& i : prog) b.emit(i);
  b.emit(abx(Op::STA_64, result, kOut));
  b.emit(abc(Op::RET, 0));
  EXPECT_EQ(bc::verifyModule(b.m), "");
  vm::Machine vm(b.m);
  vm.coldStart();
  EXPECT_TRUE(vm.run(0, 0)) << vm.fault().describe(b.m);
  uint64_t v;
  std::memcpy(&v, vm.memory() + kOut, 8);
  return v;
}
int64_t evalI(std::vector<bc::Instr> prog, uint16_t result) { return static_cast<int64_t>(eval(prog, result)); }

uint64_t bitsOf(double d) { return std::bit_cast<uint64_t>(d); }
double evalF(std::vector<bc::Instr> prog, uint16_t result, std::vector<double> ks = {}) {
  std::vector<uint64_t> raw;
  for (double d : ks) raw.push_back(bitsOf(d));
  return std::bit_cast<double>(eval(prog, result, raw));
}

TEST(MachineCore, IntegerArithmeticWraps) {
  EXPECT_EQ(evalI({asbx(Op::LDI, 2, 40), asbx(Op::LDI, 3, 2), abc(Op::ADD, 4, 2, 3)}, 4), 42);
  EXPECT_EQ(evalI({asbx(Op::LDI, 2, 5), asbx(Op::LDI, 3, 7), abc(Op::SUB, 4, 2, 3)}, 4), -2);
  EXPECT_EQ(evalI({asbx(Op::LDI, 2, -6), asbx(Op::LDI, 3, 7), abc(Op::MUL, 4, 2, 3)}, 4), -42);
  EXPECT_EQ(evalI({asbx(Op::LDI, 2, -7), asbx(Op::LDI, 3, 2), abc(Op::DIV_I, 4, 2, 3)}, 4), -3);
  EXPECT_EQ(evalI({asbx(Op::LDI, 2, -7), asbx(Op::LDI, 3, 2), abc(Op::MOD_I, 4, 2, 3)}, 4), -1);
  EXPECT_EQ(eval({asbx(Op::LDI, 2, -1), asbx(Op::LDI, 3, 2), abc(Op::DIV_U, 4, 2, 3)}, 4), UINT64_MAX / 2);
  EXPECT_EQ(eval({asbx(Op::LDI, 2, 17), asbx(Op::LDI, 3, 5), abc(Op::MOD_U, 4, 2, 3)}, 4), 2u);
  EXPECT_EQ(evalI({asbx(Op::LDI, 2, 10), abc(Op::ADDI, 3, 2, static_cast<uint16_t>(-3))}, 3), 7);
  EXPECT_EQ(evalI({asbx(Op::LDI, 2, 9), abc(Op::NEG, 3, 2)}, 3), -9);
  // INT64_MIN / -1 and INT64_MIN * -1 wrap instead of trapping.
  const uint64_t minI = uint64_t{1} << 63;
  EXPECT_EQ(eval({abx(Op::LDK, 2, 0), asbx(Op::LDI, 3, -1), abc(Op::DIV_I, 4, 2, 3)}, 4, {minI}), minI);
  EXPECT_EQ(eval({abx(Op::LDK, 2, 0), asbx(Op::LDI, 3, -1), abc(Op::MOD_I, 4, 2, 3)}, 4, {minI}), 0u);
  EXPECT_EQ(eval({abx(Op::LDK, 2, 0), abc(Op::NEG, 3, 2)}, 3, {minI}), minI);
  EXPECT_EQ(eval({abx(Op::LDK, 2, 0), asbx(Op::LDI, 3, -1), abc(Op::ADD, 4, 2, 3)}, 4, {minI}), minI - 1);
}

TEST(MachineCore, NarrowingWithSextZext) {
  // INT 32767 + 1 = -32768
  EXPECT_EQ(evalI({asbx(Op::LDI, 2, 32767), abc(Op::ADDI, 2, 2, 1), abc(Op::SEXT, 3, 2, 16)}, 3), -32768);
  // USINT 250 + 10 = 4
  EXPECT_EQ(evalI({asbx(Op::LDI, 2, 250), abc(Op::ADDI, 2, 2, 10), abc(Op::ZEXT, 3, 2, 8)}, 3), 4);
  EXPECT_EQ(eval({asbx(Op::LDI, 2, -1), abc(Op::ZEXT, 3, 2, 64)}, 3), UINT64_MAX);
  EXPECT_EQ(evalI({asbx(Op::LDI, 2, 1), abc(Op::SEXT, 3, 2, 1)}, 3), -1);
  EXPECT_EQ(evalI({asbx(Op::LDI, 2, -5), abc(Op::SEXT, 3, 2, 64)}, 3), -5);
}

TEST(MachineCore, BitsAndShifts) {
  EXPECT_EQ(eval({asbx(Op::LDI, 2, 0b1100), asbx(Op::LDI, 3, 0b1010), abc(Op::BAND, 4, 2, 3)}, 4), 0b1000u);
  EXPECT_EQ(eval({asbx(Op::LDI, 2, 0b1100), asbx(Op::LDI, 3, 0b1010), abc(Op::BOR, 4, 2, 3)}, 4), 0b1110u);
  EXPECT_EQ(eval({asbx(Op::LDI, 2, 0b1100), asbx(Op::LDI, 3, 0b1010), abc(Op::BXOR, 4, 2, 3)}, 4), 0b0110u);
  EXPECT_EQ(eval({asbx(Op::LDI, 2, 0), abc(Op::BNOT, 3, 2)}, 3), UINT64_MAX);
  EXPECT_EQ(eval({asbx(Op::LDI, 2, 0), abc(Op::LNOT, 3, 2)}, 3), 1u);
  EXPECT_EQ(eval({asbx(Op::LDI, 2, 7), abc(Op::LNOT, 3, 2)}, 3), 0u);
  EXPECT_EQ(eval({asbx(Op::LDI, 2, 1), asbx(Op::LDI, 3, 63), abc(Op::SHL, 4, 2, 3)}, 4), uint64_t{1} << 63);
  EXPECT_EQ(eval({asbx(Op::LDI, 2, 1), asbx(Op::LDI, 3, 64), abc(Op::SHL, 4, 2, 3)}, 4), 0u);
  EXPECT_EQ(eval({asbx(Op::LDI, 2, -1), asbx(Op::LDI, 3, 60), abc(Op::SHR, 4, 2, 3)}, 4), 15u);
  EXPECT_EQ(eval({asbx(Op::LDI, 2, -1), asbx(Op::LDI, 3, 200), abc(Op::SHR, 4, 2, 3)}, 4), 0u);
  EXPECT_EQ(eval({asbx(Op::LDI, 2, -1), asbx(Op::LDI, 3, -1), abc(Op::SHR, 4, 2, 3)}, 4), 0u);
}

TEST(MachineCore, Comparisons) {
  auto cmp = [](Op op, int32_t x, int32_t y) {
    return eval({asbx(Op::LDI, 2, x), asbx(Op::LDI, 3, y), abc(op, 4, 2, 3)}, 4);
  };
  EXPECT_EQ(cmp(Op::EQ, 3, 3), 1u);
  EXPECT_EQ(cmp(Op::NE, 3, 3), 0u);
  EXPECT_EQ(cmp(Op::LT_I, -1, 0), 1u);
  EXPECT_EQ(cmp(Op::LT_U, -1, 0), 0u);
  EXPECT_EQ(cmp(Op::LE_I, 2, 2), 1u);
  EXPECT_EQ(cmp(Op::LE_U, 3, 2), 0u);
  auto cmpF = [](Op op, double x, double y) {
    return eval({abx(Op::LDK, 2, 0), abx(Op::LDK, 3, 1), abc(op, 4, 2, 3)}, 4, {bitsOf(x), bitsOf(y)});
  };
  EXPECT_EQ(cmpF(Op::EQ_F, 0.0, -0.0), 1u);
  EXPECT_EQ(cmpF(Op::NE_F, NAN, NAN), 1u);
  EXPECT_EQ(cmpF(Op::LT_F, -1.5, 1.0), 1u);
  EXPECT_EQ(cmpF(Op::LE_F, NAN, 1.0), 0u);
}

TEST(MachineCore, ImmediateOperands) {
  auto cmpK = [](Op op, int32_t x, int16_t k) {
    return eval({asbx(Op::LDI, 2, x), abc(op, 3, 2, static_cast<uint16_t>(k))}, 3);
  };
  EXPECT_EQ(cmpK(Op::EQK, -3, -3), 1u);
  EXPECT_EQ(cmpK(Op::NEK, -3, -3), 0u);
  EXPECT_EQ(cmpK(Op::LTK, -40000, -32768), 1u);  // the register is not truncated to 16 bits
  EXPECT_EQ(cmpK(Op::LEK, 5, 5), 1u);
  EXPECT_EQ(cmpK(Op::GTK, 5, 5), 0u);
  EXPECT_EQ(cmpK(Op::GEK, 70000, 32767), 1u);
  // DIVK/MODK: C is an unsigned divisor; signed dividends truncate toward zero.
  EXPECT_EQ(evalI({asbx(Op::LDI, 2, -7), abc(Op::DIVK, 3, 2, 2)}, 3), -3);
  EXPECT_EQ(evalI({asbx(Op::LDI, 2, -7), abc(Op::MODK, 3, 2, 3)}, 3), -1);
  EXPECT_EQ(evalI({asbx(Op::LDI, 2, 100000), abc(Op::DIVK, 3, 2, 65535)}, 3), 1);
  EXPECT_EQ(evalI({asbx(Op::LDI, 2, 100000), abc(Op::MODK, 3, 2, 65535)}, 3), 34465);
  // STK_*: A is the value (sign-extended), truncated to the width like any store.
  ModuleBuilder b;
  b.poke<uint64_t>(120, ~uint64_t{0});
  b.beginPou("MAIN", 4);
  b.emit(abc(Op::STK_8, static_cast<uint16_t>(-2), 1, 0));
  b.emit(abc(Op::STK_16, 300, 1, 2));
  b.emit(abc(Op::STK_32, static_cast<uint16_t>(-1), 1, 4));
  b.emit(abc(Op::STK_64, static_cast<uint16_t>(-32768), 1, 8));
  b.emit(abc(Op::STK_8, 1, 1, 20));  // only the low byte of the 8 at 120
  b.emit(abc(Op::RET));
  ASSERT_EQ(bc::verifyModule(b.m), "");
  vm::Machine vm(b.m);
  vm.coldStart();
  ASSERT_TRUE(vm.run(0, 100)) << vm.fault().describe(b.m);
  auto rd = [&](uint32_t a, auto v) { std::memcpy(&v, vm.memory() + a, sizeof v); return v; };
  EXPECT_EQ(rd(100, uint8_t{}), 0xfeu);
  EXPECT_EQ(rd(102, uint16_t{}), 300u);
  EXPECT_EQ(rd(104, uint32_t{}), 0xffffffffu);
  EXPECT_EQ(rd(108, int64_t{}), -32768);
  EXPECT_EQ(rd(120, uint64_t{}), 0xffffffffffffff01u);
}

TEST(MachineCore, ImmediateStoreIsBoundsChecked) {
  ModuleBuilder b;
  b.beginPou("MAIN", 4);
  b.emit(abc(Op::STK_32, 1, 1, 0), 7, 3);
  b.emit(abc(Op::RET));
  vm::Machine vm(b.m);
  vm.coldStart();
  EXPECT_FALSE(vm.run(0, 0));  // this = 0: below the null guard
  EXPECT_EQ(vm.fault().kind, bc::FaultKind::InvalidPointer);
  EXPECT_EQ(vm.fault().loc.line, 7u);
}

TEST(MachineCore, NativeFbCallIsBoundsChecked) {
  ModuleBuilder b;
  b.poke<uint8_t>(100, 1);  // R_TRIG at 100: CLK = TRUE
  b.beginPou("MAIN", 4);
  b.emit(abx(Op::CALLFB, 1, static_cast<uint32_t>(bc::NativeFb::R_TRIG)), 3, 1);
  b.emit(abc(Op::RET));
  ASSERT_EQ(bc::verifyModule(b.m), "");
  vm::Machine vm(b.m);
  vm.coldStart();
  ASSERT_TRUE(vm.run(0, 100)) << vm.fault().describe(b.m);
  EXPECT_EQ(vm.memory()[101], 1u);  // Q: rising edge
  EXPECT_EQ(vm.memory()[102], 1u);  // M
  // The instance must lie inside memory: its last byte would be past the end here.
  EXPECT_FALSE(vm.run(0, vm.memorySize() - 2));
  EXPECT_EQ(vm.fault().kind, bc::FaultKind::InvalidPointer);
  EXPECT_EQ(vm.fault().loc.line, 3u);
}

TEST(MachineCore, NativeTimerReadsTheTaskTime) {
  ModuleBuilder b;
  b.poke<uint8_t>(100, 1);      // TON at 100: IN = TRUE
  b.poke<int32_t>(104, 20);     // PT = T#20ms
  b.beginPou("MAIN", 4);
  b.emit(abx(Op::CALLFB, 1, static_cast<uint32_t>(bc::NativeFb::TON)));
  b.emit(abc(Op::RET));
  vm::Machine vm(b.m);
  vm.coldStart();
  const int64_t ms = 1'000'000;
  for (int64_t t : {5 * ms, 15 * ms, 25 * ms}) {
    vm.setTaskTimeNs(t);
    ASSERT_TRUE(vm.run(0, 100));
  }
  int32_t et;
  std::memcpy(&et, vm.memory() + 112, 4);
  EXPECT_EQ(et, 20);                // started at 5 ms, 20 ms elapsed
  EXPECT_EQ(vm.memory()[108], 1u);  // Q
  EXPECT_EQ(vm.timeReads(), 3u);
}

TEST(MachineCore, IndexScalesAndChecks) {
  auto index = [](int32_t i, bc::IndexDesc d) {
    ModuleBuilder b;
    b.m.indexes.push_back(d);
    b.beginPou("MAIN", 4);
    b.emit(asbx(Op::LDI, 2, i));
    b.emit(abc(Op::INDEX, 3, 2, 0), 5, 7);
    b.emit(abx(Op::STA_64, 3, kOut));
    b.emit(abc(Op::RET));
    EXPECT_EQ(bc::verifyModule(b.m), "");
    vm::Machine vm(b.m);
    vm.coldStart();
    if (!vm.run(0, 0)) return vm.fault().describe(b.m);
    uint64_t v;
    std::memcpy(&v, vm.memory() + kOut, 8);
    return std::to_string(v);
  };
  EXPECT_EQ(index(1, {1, 8, 64}), "0");
  EXPECT_EQ(index(8, {1, 8, 64}), "448");
  EXPECT_EQ(index(-3, {-5, 3, 2}), "4");
  EXPECT_EQ(index(9, {1, 8, 64}), "array index out of range at MAIN.st:5:7");
  EXPECT_EQ(index(0, {1, 8, 64}), "array index out of range at MAIN.st:5:7");
  EXPECT_EQ(index(-6, {-5, 3, 2}), "array index out of range at MAIN.st:5:7");
}

TEST(MachineCore, FloatArithmetic) {
  std::vector<double> k = {0.1, 0.2};
  auto bin = [&](Op op) { return evalF({abx(Op::LDK, 2, 0), abx(Op::LDK, 3, 1), abc(op, 4, 2, 3)}, 4, k); };
  EXPECT_EQ(bin(Op::ADD_F), 0.1 + 0.2);
  EXPECT_EQ(bin(Op::SUB_F), 0.1 - 0.2);
  EXPECT_EQ(bin(Op::MUL_F), 0.1 * 0.2);
  EXPECT_EQ(bin(Op::DIV_F), 0.1 / 0.2);
  EXPECT_EQ(bin(Op::ADD_F32), static_cast<double>(static_cast<float>(0.1 + 0.2)));
  EXPECT_EQ(bin(Op::SUB_F32), static_cast<double>(static_cast<float>(0.1 - 0.2)));
  EXPECT_EQ(bin(Op::MUL_F32), static_cast<double>(static_cast<float>(0.1 * 0.2)));
  EXPECT_EQ(bin(Op::DIV_F32), static_cast<double>(static_cast<float>(0.1 / 0.2)));
  EXPECT_EQ(evalF({abx(Op::LDK, 2, 0), abc(Op::NEG_F, 3, 2)}, 3, k), -0.1);
  EXPECT_EQ(evalF({abx(Op::LDK, 2, 0), abc(Op::RND_F32, 3, 2)}, 3, k), static_cast<double>(0.1f));
  // Division by zero is IEEE, not a fault.
  EXPECT_TRUE(std::isinf(evalF({abx(Op::LDK, 2, 0), abx(Op::LDK, 3, 1), abc(Op::DIV_F, 4, 2, 3)}, 4, {1.0, 0.0})));
}

TEST(MachineCore, Conversions) {
  auto f2i = [](Op op, double d) {
    return static_cast<int64_t>(eval({abx(Op::LDK, 2, 0), abc(op, 3, 2)}, 3, {bitsOf(d)}));
  };
  EXPECT_EQ(f2i(Op::F2I, 3.7), 4);
  EXPECT_EQ(f2i(Op::F2I, -3.7), -4);
  EXPECT_EQ(f2i(Op::F2I, 2.5), 3);
  EXPECT_EQ(f2i(Op::F2I, -2.5), -3);
  EXPECT_EQ(f2i(Op::F2I, NAN), 0);
  EXPECT_EQ(f2i(Op::F2I, 1e300), INT64_MAX);
  EXPECT_EQ(f2i(Op::F2I, -1e300), INT64_MIN);
  EXPECT_EQ(f2i(Op::F2I, INFINITY), INT64_MAX);
  EXPECT_EQ(f2i(Op::F2I_TRUNC, -3.7), -3);
  EXPECT_EQ(f2i(Op::F2I_TRUNC, 3.99), 3);
  EXPECT_EQ(f2i(Op::F2I_TRUNC, NAN), 0);
  EXPECT_EQ(f2i(Op::F2I_TRUNC, 9.3e18), INT64_MAX);
  EXPECT_EQ(static_cast<uint64_t>(f2i(Op::F2U, 2.5)), 3u);
  EXPECT_EQ(static_cast<uint64_t>(f2i(Op::F2U, -7.0)), 0u);
  EXPECT_EQ(static_cast<uint64_t>(f2i(Op::F2U, 1e30)), UINT64_MAX);
  EXPECT_EQ(static_cast<uint64_t>(f2i(Op::F2U, NAN)), 0u);
  EXPECT_EQ(evalF({asbx(Op::LDI, 2, -3), abc(Op::I2F, 3, 2)}, 3), -3.0);
  EXPECT_EQ(evalF({asbx(Op::LDI, 2, -1), abc(Op::U2F, 3, 2)}, 3), 18446744073709551615.0);
}

TEST(MachineCore, LoadsAndStoresRegisterRelative) {
  ModuleBuilder b;
  b.poke<int16_t>(100, -2);
  b.poke<float>(104, 1.5f);
  b.poke<uint8_t>(110, 0b0100);
  b.beginPou("MAIN", 8);
  // r1 = this = 100
  b.emit(abc(Op::LD_I16, 2, 1, 0));   // -2
  b.emit(abc(Op::LD_U16, 3, 1, 0));   // 65534
  b.emit(abc(Op::LD_F32, 4, 1, 4));   // 1.5
  b.emit(abc(Op::ST_32, 2, 1, 20));   // mem[120] = 0xfffffffe
  b.emit(abc(Op::ST_F32, 4, 1, 24));  // mem[124] = 1.5f
  b.emit(abc(Op::ST_64, 3, 1, 28));   // mem[128] = 65534
  b.emit(abc(Op::ST_16, 2, 1, 36));   // mem[136] = 0xfffe
  b.emit(abc(Op::ST_8, 2, 1, 38));    // mem[138] = 0xfe
  b.emit(abc(Op::LD_I8, 6, 1, 38));
  b.emit(abc(Op::ST_64, 6, 1, 40));   // mem[140] = -2
  b.emit(abc(Op::LD_I32, 7, 1, 20));
  b.emit(abc(Op::ST_64, 7, 1, 48));   // mem[148] = -2
  b.emit(abc(Op::LD_U32, 7, 1, 20));
  b.emit(abc(Op::ST_64, 7, 1, 56));   // mem[156] = 0xfffffffe
  b.emit(abc(Op::LD_U8, 7, 1, 38));
  b.emit(abc(Op::ST_64, 7, 1, 64));   // mem[164] = 0xfe
  b.emit(abc(Op::LD_64, 7, 1, 64));
  b.emit(abc(Op::ST_64, 7, 1, 72));   // mem[172] = 0xfe
  b.emit(abc(Op::RET));
  vm::Machine vm(b.m);
  vm.coldStart();
  ASSERT_TRUE(vm.run(0, 100)) << vm.fault().describe(b.m);
  auto rd = [&](uint32_t a, auto v) { std::memcpy(&v, vm.memory() + a, sizeof v); return v; };
  EXPECT_EQ(rd(120, uint32_t{}), 0xfffffffeu);
  EXPECT_EQ(rd(124, float{}), 1.5f);
  EXPECT_EQ(rd(128, uint64_t{}), 65534u);
  EXPECT_EQ(rd(136, uint16_t{}), 0xfffeu);
  EXPECT_EQ(rd(138, uint8_t{}), 0xfeu);
  EXPECT_EQ(rd(140, int64_t{}), -2);
  EXPECT_EQ(rd(148, int64_t{}), -2);
  EXPECT_EQ(rd(156, uint64_t{}), 0xfffffffeu);
  EXPECT_EQ(rd(164, uint64_t{}), 0xfeu);
  EXPECT_EQ(rd(172, uint64_t{}), 0xfeu);
}

TEST(MachineCore, BitAccess) {
  ModuleBuilder b;
  b.poke<uint8_t>(200, 0b0100);
  b.beginPou("MAIN", 8);
  b.emit(abx(Op::LDI, 2, 200));
  b.emit(abc(Op::LD_BIT, 3, 2, 2));  // 1
  b.emit(abc(Op::LD_BIT, 4, 2, 1));  // 0
  b.emit(abc(Op::ST_BIT, 3, 2, 7));  // set bit 7
  b.emit(abc(Op::ST_BIT, 4, 2, 2));  // clear bit 2
  b.emit(abx(Op::STA_64, 3, 208));
  b.emit(abx(Op::STA_64, 4, 216));
  b.emit(abc(Op::RET));
  vm::Machine vm(b.m);
  vm.coldStart();
  ASSERT_TRUE(vm.run(0, 0));
  EXPECT_EQ(vm.memory()[200], 0x80);
  EXPECT_EQ(vm.memory()[208], 1);
  EXPECT_EQ(vm.memory()[216], 0);
}

TEST(MachineCore, AbsoluteLoadsAndStores) {
  ModuleBuilder b;
  b.poke<int8_t>(100, -3);
  b.poke<int16_t>(102, -300);
  b.poke<int32_t>(104, -70000);
  b.poke<float>(108, 2.25f);
  b.poke<uint64_t>(112, 0x1122334455667788u);
  b.beginPou("MAIN", 12);
  b.emit(abx(Op::LDA_I8, 2, 100));
  b.emit(abx(Op::LDA_U8, 3, 100));
  b.emit(abx(Op::LDA_I16, 4, 102));
  b.emit(abx(Op::LDA_U16, 5, 102));
  b.emit(abx(Op::LDA_I32, 6, 104));
  b.emit(abx(Op::LDA_U32, 7, 104));
  b.emit(abx(Op::LDA_F32, 8, 108));
  b.emit(abx(Op::LDA_64, 9, 112));
  b.emit(abx(Op::STA_64, 2, 200));
  b.emit(abx(Op::STA_64, 3, 208));
  b.emit(abx(Op::STA_64, 4, 216));
  b.emit(abx(Op::STA_64, 5, 224));
  b.emit(abx(Op::STA_64, 6, 232));
  b.emit(abx(Op::STA_64, 7, 240));
  b.emit(abx(Op::STA_F32, 8, 248));
  b.emit(abx(Op::STA_8, 9, 252));
  b.emit(abx(Op::STA_16, 9, 254));
  b.emit(abx(Op::STA_32, 9, 256));
  b.emit(abc(Op::RET));
  vm::Machine vm(b.m);
  vm.coldStart();
  ASSERT_TRUE(vm.run(0, 0));
  auto rd = [&](uint32_t a, auto v) { std::memcpy(&v, vm.memory() + a, sizeof v); return v; };
  EXPECT_EQ(rd(200, int64_t{}), -3);
  EXPECT_EQ(rd(208, int64_t{}), 253);
  EXPECT_EQ(rd(216, int64_t{}), -300);
  EXPECT_EQ(rd(224, int64_t{}), 65236);
  EXPECT_EQ(rd(232, int64_t{}), -70000);
  EXPECT_EQ(rd(240, int64_t{}), int64_t{0xFFFEEE90});
  EXPECT_EQ(rd(248, float{}), 2.25f);
  EXPECT_EQ(rd(252, uint8_t{}), 0x88u);
  EXPECT_EQ(rd(254, uint16_t{}), 0x7788u);
  EXPECT_EQ(rd(256, uint32_t{}), 0x55667788u);
}

TEST(MachineCore, CopyHandlesOverlap) {
  ModuleBuilder b;
  b.pokeString(100, "abcdef");
  b.beginPou("MAIN", 8);
  b.emit(abx(Op::LDI, 2, 102));
  b.emit(abx(Op::LDI, 3, 100));
  b.emit(abx(Op::LDI, 4, 4));
  b.emit(abc(Op::COPY, 2, 3, 4));  // "ababcd"
  b.emit(abc(Op::RET));
  vm::Machine vm(b.m);
  vm.coldStart();
  ASSERT_TRUE(vm.run(0, 0));
  EXPECT_STREQ(reinterpret_cast<const char*>(vm.memory() + 100), "ababcd");
}

TEST(MachineCore, LoopsWithJumps) {
  // sum = 0; i = 10; while i != 0: sum += i; i -= 1
  ModuleBuilder b;
  b.beginPou("MAIN", 8);
  b.emit(asbx(Op::LDI, 2, 0));
  b.emit(asbx(Op::LDI, 3, 10));
  b.emit(asbx(Op::JZ, 3, 3));          // pc 2 -> exit at 6
  b.emit(abc(Op::ADD, 2, 2, 3));
  b.emit(abc(Op::ADDI, 3, 3, static_cast<uint16_t>(-1)));
  b.emit(asbx(Op::JMP, 0, -4));        // back to pc 2
  b.emit(abx(Op::STA_64, 2, kOut));
  b.emit(asbx(Op::JNZ, 2, 1));         // taken: skip the next
  b.emit(abx(Op::STA_64, 3, kOut));
  b.emit(abc(Op::RET));
  vm::Machine vm(b.m);
  vm.coldStart();
  ASSERT_TRUE(vm.run(0, 0));
  EXPECT_EQ(vm.memory()[kOut], 55);
  EXPECT_EQ(vm.instructionsExecuted(), 0u);  // not counted unless asked for
  vm.countInstructions(true);
  ASSERT_TRUE(vm.run(0, 0));
  EXPECT_GT(vm.instructionsExecuted(), 40u);
}

TEST(MachineCore, LdkAndSystime) {
  ModuleBuilder b;
  b.constant(0xdeadbeefcafef00d);
  b.beginPou("MAIN", 4);
  b.emit(abx(Op::LDK, 2, 0));
  b.emit(abc(Op::SYSTIME, 3));
  b.emit(abx(Op::STA_64, 2, 16));
  b.emit(abx(Op::STA_64, 3, 24));
  b.emit(abc(Op::NOP));
  b.emit(abc(Op::MOV, 2, 3));
  b.emit(abx(Op::STA_64, 2, 32));
  b.emit(abc(Op::RET));
  vm::Machine vm(b.m);
  vm.coldStart();
  vm.setTaskTimeNs(123'000'000);
  ASSERT_TRUE(vm.run(0, 0));
  auto rd = [&](uint32_t a) { uint64_t v; std::memcpy(&v, vm.memory() + a, 8); return v; };
  EXPECT_EQ(rd(16), 0xdeadbeefcafef00du);
  EXPECT_EQ(rd(24), 123'000'000u);
  EXPECT_EQ(rd(32), 123'000'000u);
}

}  // namespace
}  // namespace virtcom
