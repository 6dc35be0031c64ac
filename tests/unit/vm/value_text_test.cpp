// resolveVariable, formatValue and writeValueFromText over a hand-made type table.
#include <gtest/gtest.h>

#include <cstring>

#include "bytecode/module.hpp"

namespace virtcom {
namespace {

using bc::ArrayDim;
using bc::Field;
using bc::TypeDesc;
using bc::TypeId;
using bc::TypeKind;

TypeDesc elem(ElemType e, uint32_t size) {
  TypeDesc t;
  t.kind = TypeKind::Elementary;
  t.elem = e;
  t.name = std::string(elemTypeInfo(e).name);
  t.size = size;
  return t;
}

TypeDesc desc(TypeKind kind, std::string name, uint32_t size, uint32_t align, ElemType e = ElemType::Bool) {
  TypeDesc t;
  t.kind = kind;
  t.name = std::move(name);
  t.size = size;
  t.align = align;
  t.elem = e;
  return t;
}

Field field(std::string name, TypeId type, uint32_t offset, bool hidden = false) {
  Field f;
  f.name = std::move(name);
  f.type = type;
  f.offset = offset;
  f.hidden = hidden;
  return f;
}

enum : TypeId { kBool, kInt, kUsint, kWord, kTime, kStr10, kColor, kPoint, kPoints, kGrid, kMain, kLreal,
                kWstr5, kPtr, kReal, kLtime, kDate, kTod, kDt, kUlint, kSint, kLint, kPacked, kPrg };

// MAIN (at 100): pts : ARRAY[1..3] OF Point; grid : ARRAY[0..1, 1..3] OF INT; color : Color;
// name : STRING(10); t : TIME; w : WORD; b : USINT; lr : LREAL; wname : WSTRING(5); p : POINTER TO INT.
bc::Module makeModule() {
  bc::Module m;
  m.staticSize = 1024;
  m.initialImage.assign(1024, 0);
  auto& T = m.types;
  T.push_back(elem(ElemType::Bool, 1));
  T.push_back(elem(ElemType::Int, 2));
  T.push_back(elem(ElemType::Usint, 1));
  T.push_back(elem(ElemType::Word, 2));
  T.push_back(elem(ElemType::Time, 4));
  TypeDesc s10 = desc(TypeKind::String, "STRING(10)", 11, 1, ElemType::String);
  s10.stringLength = 10;
  T.push_back(s10);
  TypeDesc color = desc(TypeKind::Enum, "Color", 2, 2, ElemType::Int);
  color.enumerators = {{"Red", 0}, {"Green", 1}, {"Blue", 5}};
  T.push_back(color);
  TypeDesc point = desc(TypeKind::Struct, "Point", 8, 2);
  point.fields = {field("x", kInt, 0), field("y", kInt, 2), field("flag", kBool, 4), field("secret", kInt, 6, true)};
  T.push_back(point);
  TypeDesc pts = desc(TypeKind::Array, "ARRAY [1..3] OF Point", 24, 2);
  pts.element = kPoint;
  pts.dims = {ArrayDim{1, 3}};
  T.push_back(pts);
  TypeDesc grid = desc(TypeKind::Array, "ARRAY [0..1, 1..3] OF INT", 12, 2);
  grid.element = kInt;
  grid.dims = {ArrayDim{0, 1}, ArrayDim{1, 3}};
  T.push_back(grid);
  TypeDesc main = desc(TypeKind::Struct, "MAIN", 88, 8);
  main.fields = {field("pts", kPoints, 0), field("grid", kGrid, 24), field("color", kColor, 36),
                 field("name", kStr10, 38), field("t", kTime, 52), field("w", kWord, 56), field("b", kUsint, 58),
                 field("lr", kLreal, 64), field("wname", kWstr5, 72), field("p", kPtr, 84)};
  T.push_back(main);
  T.push_back(elem(ElemType::Lreal, 8));
  TypeDesc w5 = desc(TypeKind::String, "WSTRING(5)", 12, 2, ElemType::Wstring);
  w5.stringLength = 5;
  T.push_back(w5);
  TypeDesc ptr = desc(TypeKind::Pointer, "POINTER TO INT", 4, 4);
  ptr.element = kInt;
  T.push_back(ptr);
  T.push_back(elem(ElemType::Real, 4));
  T.push_back(elem(ElemType::Ltime, 8));
  T.push_back(elem(ElemType::Date, 4));
  T.push_back(elem(ElemType::Tod, 4));
  T.push_back(elem(ElemType::Dt, 4));
  T.push_back(elem(ElemType::Ulint, 8));
  T.push_back(elem(ElemType::Sint, 1));
  T.push_back(elem(ElemType::Lint, 8));
  TypeDesc packed = desc(TypeKind::Struct, "IO", 2, 1);
  Field bit = field("ready", kBool, 0);
  bit.bit = 3;
  Field bit2 = field("done", kBool, 0);
  bit2.bit = 9;
  packed.fields = {bit, bit2};
  T.push_back(packed);
  TypeDesc prg = desc(TypeKind::Struct, "PRG", 2, 2);  // a program with a located member
  Field sensor = field("sensor", kBool, 600);
  sensor.bit = 3;
  sensor.absolute = true;
  prg.fields = {field("local", kInt, 0), sensor, field("level", kInt, 602)};
  prg.fields.back().absolute = true;
  T.push_back(prg);
  m.symbols = {{"MAIN", kMain, 100, false}, {"GVL.counter", kInt, 300, false}, {"x", kUsint, 302, false},
               {"GVL.flags", kWord, 304, true}, {"GVL.io", kPacked, 306, false}, {"PRG", kPrg, 320, false}};
  return m;
}

class ValueText : public ::testing::Test {
 protected:
  bc::Module m = makeModule();
  std::vector<uint8_t> mem = std::vector<uint8_t>(m.memorySize(), 0);

  bc::VarRef ref(std::string_view path) {
    auto r = bc::resolveVariable(m, path);
    EXPECT_TRUE(r.has_value()) << path;
    return r.value_or(bc::VarRef{});
  }
  std::string show(std::string_view path) { return bc::formatValue(m, ref(path), mem.data()); }
  std::string write(std::string_view path, std::string_view text) {
    return bc::writeValueFromText(m, ref(path), text, mem.data());
  }
  // Writes text and returns the formatted result (or the error).
  std::string roundTrip(std::string_view path, std::string_view text) {
    std::string e = write(path, text);
    return e.empty() ? show(path) : "error: " + e;
  }
};

TEST_F(ValueText, ResolvesPaths) {
  EXPECT_EQ(ref("MAIN").address, 100u);
  EXPECT_EQ(ref("main.PTS[2].y").address, 100u + 8 + 2);
  EXPECT_EQ(ref("MAIN.pts[2].y").type, kInt);
  EXPECT_EQ(ref("MAIN.grid[1, 2]").address, 100u + 24 + 2 * (3 + 1));
  EXPECT_EQ(ref("MAIN.grid[1][2]").address, 100u + 24 + 2 * (3 + 1));
  EXPECT_EQ(ref(" MAIN.grid[ 0 ,3 ] ").address, 100u + 24 + 2 * 2);
  EXPECT_EQ(ref("GVL.counter").address, 300u);
  EXPECT_EQ(ref("gvl.COUNTER").address, 300u);
  EXPECT_EQ(ref("counter").address, 300u);  // unique short name
  EXPECT_EQ(ref("x").address, 302u);
  EXPECT_EQ(ref("MAIN.pts[3].secret").address, 100u + 16 + 6);  // hidden but addressable
  EXPECT_FALSE(ref("MAIN").readOnly);
  EXPECT_TRUE(ref("GVL.flags").readOnly);
}

TEST_F(ValueText, ResolvesBits) {
  bc::VarRef r = ref("MAIN.w.9");
  EXPECT_EQ(r.address, 100u + 56 + 1);
  EXPECT_EQ(r.bit, 1);
  EXPECT_EQ(r.type, kBool);
  EXPECT_EQ(ref("GVL.flags.3").bit, 3);
  EXPECT_TRUE(ref("GVL.flags.3").readOnly);
  EXPECT_EQ(ref("GVL.io.ready").bit, 3);
  EXPECT_EQ(ref("GVL.io.done").address, 307u);
  EXPECT_EQ(ref("GVL.io.done").bit, 1);
}

TEST_F(ValueText, LocatedMembersUseAbsoluteAddresses) {
  EXPECT_EQ(ref("PRG.sensor").address, 600u);
  EXPECT_EQ(ref("PRG.sensor").bit, 3);
  EXPECT_EQ(ref("PRG.level").address, 602u);
  EXPECT_EQ(roundTrip("PRG.sensor", "TRUE"), "TRUE");
  EXPECT_EQ(mem[600], 8);
  EXPECT_EQ(roundTrip("PRG.level", "-3"), "-3");
  EXPECT_EQ(roundTrip("PRG.local", "4"), "4");
  EXPECT_EQ(show("PRG"), "(local := 4, sensor := TRUE, level := -3)");
}

TEST_F(ValueText, RejectsBadPaths) {
  for (const char* p : {"MAIN.pts[4]", "MAIN.pts[0].x", "MAIN.grid[2, 1]", "MAIN.grid[1]", "MAIN.grid[1, 2, 3]",
                        "MAIN.nope", "MAIN.pts[1", "MAIN.pts[x]", "NOPE", "MAIN.w.16", "MAIN.b.8", "MAIN.t.1",
                        "MAIN.w.1.2", "MAIN.pts[1].x.", "MAIN..w", "MAIN.w.x", "MAINX", "MAIN.color.Red",
                        "GVL", ""}) {
    EXPECT_FALSE(bc::resolveVariable(m, p).has_value()) << p;
  }
}

TEST_F(ValueText, FormatsEveryKind) {
  EXPECT_EQ(roundTrip("MAIN.pts[1].x", "-7"), "-7");
  EXPECT_EQ(roundTrip("MAIN.pts[1].flag", "TRUE"), "TRUE");
  EXPECT_EQ(roundTrip("MAIN.pts[2].y", "16#7FFF"), "32767");
  EXPECT_EQ(show("MAIN.pts"), "[(x := -7, y := 0, flag := TRUE), (x := 0, y := 32767, flag := FALSE), "
                              "(x := 0, y := 0, flag := FALSE)]");
  EXPECT_EQ(roundTrip("MAIN.grid[1, 3]", "6"), "6");
  EXPECT_EQ(show("MAIN.grid"), "[0, 0, 0, 0, 0, 6]");
  EXPECT_EQ(roundTrip("MAIN.color", "Blue"), "Color#Blue");
  EXPECT_EQ(roundTrip("MAIN.color", "color#green"), "Color#Green");
  EXPECT_EQ(roundTrip("MAIN.color", "7"), "7");
  EXPECT_EQ(roundTrip("MAIN.name", "'it$'s'"), "'it$'s'");
  EXPECT_EQ(roundTrip("MAIN.name", "bare text that is long"), "'bare text '");
  EXPECT_EQ(roundTrip("MAIN.name", "'a$Nb'"), "'a$Nb'");
  EXPECT_EQ(roundTrip("MAIN.t", "T#1s500ms"), "T#1s500ms");
  EXPECT_EQ(roundTrip("MAIN.t", "time#-2m"), "T#-2m");
  EXPECT_EQ(roundTrip("MAIN.t", "1500"), "T#1s500ms");
  EXPECT_EQ(roundTrip("MAIN.t", "T#1.5h"), "T#1h30m");
  EXPECT_EQ(roundTrip("MAIN.w", "2#1010_1010"), "170");
  EXPECT_EQ(roundTrip("MAIN.w.0", "1"), "TRUE");
  EXPECT_EQ(show("MAIN.w"), "171");
  EXPECT_EQ(roundTrip("MAIN.w.7", "FALSE"), "FALSE");
  EXPECT_EQ(show("MAIN.w"), "43");
  EXPECT_EQ(roundTrip("MAIN.b", "255"), "255");
  EXPECT_EQ(roundTrip("MAIN.lr", "1E3"), "1000.0");
  EXPECT_EQ(roundTrip("MAIN.lr", "-2.5e-3"), "-0.0025");
  EXPECT_EQ(roundTrip("MAIN.wname", "\"h$\"i\""), "\"h$\"i\"");
  EXPECT_EQ(roundTrip("MAIN.wname", "äbcdefg"), "\"$00E4bcde\"");
  EXPECT_EQ(roundTrip("MAIN.p", "16#1234"), "error: cannot write a value of type POINTER TO INT from text");
  mem[184] = 0x2c;
  mem[185] = 0x01;
  EXPECT_EQ(show("MAIN.p"), "16#12C");
  EXPECT_EQ(roundTrip("GVL.io.ready", "TRUE"), "TRUE");
  EXPECT_EQ(show("GVL.io"), "(ready := TRUE, done := FALSE)");
  EXPECT_EQ(show("MAIN.pts[1]"), "(x := -7, y := 0, flag := TRUE)");
}

TEST_F(ValueText, FormatsWholeInstance) {
  write("MAIN.name", "abc");
  EXPECT_EQ(show("MAIN"),
            "(pts := [(x := 0, y := 0, flag := FALSE), (x := 0, y := 0, flag := FALSE), (x := 0, y := 0, flag := FALSE)], "
            "grid := [0, 0, 0, 0, 0, 0], color := Color#Red, name := 'abc', t := T#0ms, w := 0, b := 0, "
            "lr := 0.0, wname := \"\", p := 16#0)");
}

TEST_F(ValueText, ScalarTypesByTypeId) {
  auto at = [&](TypeId type, std::string_view text) {
    bc::VarRef r{type, 400, -1, false};
    std::string e = bc::writeValueFromText(m, r, text, mem.data());
    return e.empty() ? bc::formatValue(m, r, mem.data()) : "error: " + e;
  };
  EXPECT_EQ(at(kReal, "1.5"), "1.5");
  EXPECT_EQ(at(kReal, "0.1"), "0.1");
  EXPECT_EQ(at(kReal, "3"), "3.0");
  EXPECT_EQ(at(kLtime, "LTIME#1s5ns"), "LTIME#1s5ns");
  EXPECT_EQ(at(kLtime, "LT#1.5us"), "LTIME#1us500ns");
  EXPECT_EQ(at(kLtime, "42"), "LTIME#42ns");
  EXPECT_EQ(at(kDate, "D#2024-01-02"), "D#2024-01-02");
  EXPECT_EQ(at(kTod, "TOD#12:30:00.5"), "TOD#12:30:00.5");
  EXPECT_EQ(at(kDt, "DT#2024-01-02-12:30:00"), "DT#2024-01-02-12:30:00");
  EXPECT_EQ(at(kUlint, "18446744073709551615"), "18446744073709551615");
  EXPECT_EQ(at(kLint, "-9223372036854775808"), "-9223372036854775808");
  EXPECT_EQ(at(kSint, "-128"), "-128");
  EXPECT_EQ(at(kInt, "1_000"), "1000");
  EXPECT_EQ(at(kInt, "INT#-16#10"), "-16");
  EXPECT_EQ(at(kBool, "false"), "FALSE");
  EXPECT_EQ(at(kBool, "1"), "TRUE");
}

// Time, date and integer text goes through core/iec_literal, so --set and cell wiring accept
// what an ST literal accepts (tests/unit/core/literal_syntax_test.cpp pins that syntax).
TEST_F(ValueText, ReadsLiteralBodiesLikeTheStLexer) {
  auto at = [&](TypeId type, std::string_view text) {
    bc::VarRef r{type, 400, -1, false};
    std::string e = bc::writeValueFromText(m, r, text, mem.data());
    return e.empty() ? bc::formatValue(m, r, mem.data()) : "error: " + e;
  };
  EXPECT_EQ(at(kLtime, "ltime#1D2H3M4S5MS6US7NS"), "LTIME#1d2h3m4s5ms6us7ns");
  EXPECT_EQ(at(kLtime, "LT#1_000ms"), "LTIME#1s");
  EXPECT_EQ(at(kTime, "T#1d_2h"), "T#1d2h");
  EXPECT_EQ(at(kTime, "T#-1.5ms"), "T#-1ms");
  EXPECT_EQ(at(kTod, "time_of_day#1:2:3"), "TOD#01:02:03");
  EXPECT_EQ(at(kTod, "TOD#12:30"), "TOD#12:30:00");
  EXPECT_EQ(at(kTod, "TOD#12:30:00.1239"), "TOD#12:30:00.123");
  EXPECT_EQ(at(kDate, "date#2024-2-29"), "D#2024-02-29");
  EXPECT_EQ(at(kDate, "19724"), "D#1970-01-01");  // the raw count of seconds
  EXPECT_EQ(at(kDt, "date_and_time#2024-01-02-12:30:00.9"), "DT#2024-01-02-12:30:00");
  EXPECT_EQ(at(kWord, "16#ff_ff"), "65535");
  EXPECT_EQ(at(kWord, "8#17"), "15");
  EXPECT_EQ(at(kTime, "T#5x"), "error: invalid duration '5x'");
  EXPECT_EQ(at(kTime, "T#-"), "error: empty duration '-'");
  EXPECT_EQ(at(kLtime, "LT#99999999999d"), "error: duration out of range '99999999999d'");
  EXPECT_EQ(at(kTime, "T#25d"), "error: value out of range for TIME");
  EXPECT_EQ(at(kDate, "D#2024-02-30"), "error: invalid DATE literal 'D#2024-02-30'");
  EXPECT_EQ(at(kDate, "D#2106-02-08"), "error: invalid DATE literal 'D#2106-02-08'");  // beyond 32 bits
  EXPECT_EQ(at(kTod, "TOD#24:00"), "error: invalid TIME_OF_DAY literal 'TOD#24:00'");
  EXPECT_EQ(at(kDt, "DT#2024-01-02"), "error: invalid DATE_AND_TIME literal 'DT#2024-01-02'");
  EXPECT_EQ(at(kTime, "LT#1s"), "error: invalid TIME literal 'LT#1s'");
  EXPECT_EQ(at(kWord, "3#12"), "error: invalid WORD literal '3#12'");
  EXPECT_EQ(at(kWord, "_1"), "error: invalid WORD literal '_1'");
  EXPECT_EQ(at(kWord, "16#1_"), "error: invalid WORD literal '16#1_'");
}

TEST_F(ValueText, ReportsErrors) {
  EXPECT_EQ(write("MAIN.b", "300"), "value 300 out of range for USINT (0..255)");
  EXPECT_EQ(write("MAIN.b", "-1"), "value -1 out of range for USINT (0..255)");
  EXPECT_EQ(write("MAIN.pts[1].x", "32768"), "value 32768 out of range for INT (-32768..32767)");
  EXPECT_EQ(write("MAIN.pts[1].x", "-32769"), "value -32769 out of range for INT (-32768..32767)");
  EXPECT_FALSE(write("MAIN.pts[1].x", "-32768").size());
  EXPECT_NE(write("MAIN.pts[1].x", "1.5"), "");
  EXPECT_NE(write("MAIN.pts[1].x", "abc"), "");
  EXPECT_NE(write("MAIN.pts[1].x", "99999999999999999999999"), "");
  EXPECT_NE(write("MAIN.pts[1].x", "3#12"), "");
  EXPECT_NE(write("MAIN.pts[1].x", "1__"), "");
  EXPECT_NE(write("MAIN.pts[1].flag", "yes"), "");
  EXPECT_NE(write("MAIN.lr", "1.5x"), "");
  EXPECT_NE(write("MAIN.lr", ""), "");
  EXPECT_NE(write("MAIN.t", "T#5parsecs"), "");
  EXPECT_NE(write("MAIN.t", "T#"), "");
  EXPECT_NE(write("MAIN.t", "T#9999999h"), "");
  EXPECT_EQ(write("MAIN.color", "Purple"), "'Purple' is not a value of Color");
  EXPECT_NE(write("MAIN.pts", "[1, 2]"), "");
  EXPECT_NE(write("MAIN", "x"), "");
}

}  // namespace
}  // namespace virtcom
