// Transfers between a PLC variable's bytes and a bus tag: every storage width, the conversions
// the wiring allows, and the "bytes changed" answer the simulation uses to wake the PLC.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>

#include "core/value_codec.hpp"

namespace virtcom {
namespace {

struct Codec : ::testing::Test {
  TagBus bus;
  TagId intTag = bus.add("i", ElemType::Lint);
  TagId realTag = bus.add("r", ElemType::Lreal);
  TagId boolTag = bus.add("b", ElemType::Bool);
  std::array<uint8_t, 16> mem{};  // guard bytes after every variable stay 0
};

TEST_F(Codec, StoresEveryIntegerWidthInItsOwnBytesOnlyAndSaysWhenTheyChanged) {
  struct Case { ElemType type; int64_t value; size_t size; };
  for (Case c : {Case{ElemType::Sint, -5, 1}, {ElemType::Uint, 65535, 2}, {ElemType::Int, -300, 2}, {ElemType::Dint, -70000, 4},
                 {ElemType::Udint, 4000000000, 4}, {ElemType::Lint, -(int64_t{1} << 40), 8}, {ElemType::Time, 1500, 4}}) {
    SCOPED_TRACE(elemTypeInfo(c.type).name);
    mem.fill(0);
    bus.setInt(intTag, c.value);
    EXPECT_TRUE(storeVariable(mem.data(), -1, c.type, bus, intTag));
    EXPECT_FALSE(storeVariable(mem.data(), -1, c.type, bus, intTag));  // same bytes again
    for (size_t i = c.size; i < mem.size(); ++i) EXPECT_EQ(mem[i], 0) << "byte " << i << " written";
    bus.setInt(intTag, 0);
    loadVariable(mem.data(), -1, c.type, bus, intTag);
    EXPECT_EQ(bus.getInt(intTag), c.value);
  }
}

TEST_F(Codec, BoolVariablesHoldZeroOrOneAndBitsTouchOnlyTheirBit) {
  bus.setInt(intTag, 42);
  EXPECT_TRUE(storeVariable(mem.data(), -1, ElemType::Bool, bus, intTag));
  EXPECT_EQ(mem[0], 1);
  mem[1] = 0xF0;
  bus.setBool(boolTag, true);
  EXPECT_TRUE(storeVariable(mem.data() + 1, 2, ElemType::Bool, bus, boolTag));
  EXPECT_EQ(mem[1], 0xF4);
  EXPECT_FALSE(storeVariable(mem.data() + 1, 2, ElemType::Bool, bus, boolTag));
  bus.setBool(boolTag, false);
  loadVariable(mem.data() + 1, 2, ElemType::Bool, bus, boolTag);
  EXPECT_TRUE(bus.getBool(boolTag));
}

TEST_F(Codec, RealsConvertToIntegersRoundedAndBack) {
  bus.setReal(realTag, 2.5);
  EXPECT_TRUE(storeVariable(mem.data(), -1, ElemType::Int, bus, realTag));
  int16_t i = 0;
  std::memcpy(&i, mem.data(), 2);
  EXPECT_EQ(i, 3);
  bus.setReal(realTag, -2.5);
  storeVariable(mem.data(), -1, ElemType::Int, bus, realTag);
  std::memcpy(&i, mem.data(), 2);
  EXPECT_EQ(i, -3);
  bus.setReal(realTag, 0.1);
  EXPECT_TRUE(storeVariable(mem.data(), -1, ElemType::Real, bus, realTag));
  EXPECT_EQ(mem[4], 0);
  loadVariable(mem.data(), -1, ElemType::Real, bus, realTag);
  EXPECT_EQ(bus.getReal(realTag), static_cast<double>(0.1f));
  bus.setInt(intTag, 7);
  EXPECT_TRUE(storeVariable(mem.data(), -1, ElemType::Lreal, bus, intTag));
  loadVariable(mem.data(), -1, ElemType::Lreal, bus, realTag);
  EXPECT_EQ(bus.getReal(realTag), 7.0);
}

TEST_F(Codec, ANanWrittenOverItselfIsNoChange) {
  bus.setReal(realTag, std::numeric_limits<double>::quiet_NaN());
  EXPECT_TRUE(storeVariable(mem.data(), -1, ElemType::Lreal, bus, realTag));
  EXPECT_FALSE(storeVariable(mem.data(), -1, ElemType::Lreal, bus, realTag));
}

}  // namespace
}  // namespace virtcom
