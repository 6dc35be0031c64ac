// CALLN natives: math, rotation and every string function with truncation and edge positions.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <map>

#include "core/iec_value.hpp"
#include "bytecode/verifier.hpp"
#include "test_module_builder.hpp"
#include "vm/machine.hpp"

namespace virtcom {
namespace {

using bc::FaultKind;
using bc::Native;
using bc::Op;
using test::abc;
using test::abx;
using test::ModuleBuilder;

constexpr uint64_t kDst = 200, kA = 300, kB = 400;

struct NativeResult {
  bool ok = false;
  FaultKind fault = FaultKind::None;
  uint64_t r = 0;
  std::string dst;   // the string at kDst afterwards
  std::string wdst;  // the WSTRING at kDst afterwards, code units narrowed to bytes
};

// UTF-16LE bytes of an ASCII text (without terminator).
std::string wide(std::string_view ascii) {
  std::string out;
  for (char ch : ascii) {
    out += ch;
    out += '\0';
  }
  return out;
}

// Calls native n with args in r2.. and the given strings preloaded (kDst is prefilled with "#").
NativeResult callN(Native n, std::vector<uint64_t> args, std::map<uint32_t, std::string> strings = {}) {
  ModuleBuilder b;
  b.pokeString(kDst, "#");
  for (auto& [addr, s] : strings) {
    std::memcpy(b.m.initialImage.data() + addr, s.data(), s.size());
    b.m.initialImage[addr + s.size()] = 0;
    b.m.initialImage[addr + s.size() + 1] = 0;
  }
  for (uint64_t a : args) b.constant(a);
  b.beginPou("MAIN", 10);
  for (uint16_t i = 0; i < args.size(); ++i) b.emit(abx(Op::LDK, 2 + i, i));
  b.emit(abx(Op::CALLN, 2, static_cast<uint32_t>(n)), 3, 1);
  b.emit(abx(Op::STA_64, 2, 16));
  b.emit(abc(Op::RET));
  EXPECT_EQ(bc::verifyModule(b.m), "");
  vm::Machine vm(b.m);
  vm.coldStart();
  NativeResult res;
  res.ok = vm.run(0, 0);
  res.fault = vm.fault().kind;
  std::memcpy(&res.r, vm.memory() + 16, 8);
  res.dst = reinterpret_cast<const char*>(vm.memory() + kDst);
  for (const uint8_t* p = vm.memory() + kDst; p[0] || p[1]; p += 2)
    res.wdst += p[1] ? '?' : static_cast<char>(p[0]);
  return res;
}

uint64_t f(double d) { return std::bit_cast<uint64_t>(d); }
uint64_t i(int64_t v) { return static_cast<uint64_t>(v); }
double asF(uint64_t v) { return std::bit_cast<double>(v); }

// Runs a (dst, cap, ...) string native; returns the destination text.
std::string str(Native n, std::vector<uint64_t> rest, std::string a = "", std::string b = "", uint64_t cap = 80) {
  std::vector<uint64_t> args = {kDst, cap};
  args.insert(args.end(), rest.begin(), rest.end());
  NativeResult r = callN(n, args, {{kA, a}, {kB, b}});
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.r, 0u);
  return r.dst;
}

TEST(Natives, Math) {
  EXPECT_EQ(asF(callN(Native::SQRT, {f(2.0)}).r), std::sqrt(2.0));
  EXPECT_EQ(asF(callN(Native::LN, {f(10.0)}).r), std::log(10.0));
  EXPECT_EQ(asF(callN(Native::LOG, {f(1000.0)}).r), 3.0);
  EXPECT_EQ(asF(callN(Native::EXP, {f(1.0)}).r), std::exp(1.0));
  EXPECT_EQ(asF(callN(Native::SIN, {f(0.5)}).r), std::sin(0.5));
  EXPECT_EQ(asF(callN(Native::COS, {f(0.5)}).r), std::cos(0.5));
  EXPECT_EQ(asF(callN(Native::TAN, {f(0.5)}).r), std::tan(0.5));
  EXPECT_EQ(asF(callN(Native::ASIN, {f(0.5)}).r), std::asin(0.5));
  EXPECT_EQ(asF(callN(Native::ACOS, {f(0.5)}).r), std::acos(0.5));
  EXPECT_EQ(asF(callN(Native::ATAN, {f(0.5)}).r), std::atan(0.5));
  EXPECT_EQ(asF(callN(Native::ATAN2, {f(1.0), f(-1.0)}).r), std::atan2(1.0, -1.0));
  EXPECT_EQ(asF(callN(Native::EXPT, {f(2.0), f(10.0)}).r), 1024.0);
  EXPECT_EQ(asF(callN(Native::FABS, {f(-2.5)}).r), 2.5);
  EXPECT_EQ(asF(callN(Native::FTRUNC, {f(-2.7)}).r), -2.0);
  EXPECT_TRUE(std::isnan(asF(callN(Native::SQRT, {f(-1.0)}).r)));
}

TEST(Natives, Rotate) {
  EXPECT_EQ(callN(Native::ROL, {0x81, 1, 8}).r, 0x03u);
  EXPECT_EQ(callN(Native::ROR, {0x81, 1, 8}).r, 0xC0u);
  EXPECT_EQ(callN(Native::ROL, {0x8001, 4, 16}).r, 0x0018u);
  EXPECT_EQ(callN(Native::ROL, {0x12, 8, 8}).r, 0x12u);
  EXPECT_EQ(callN(Native::ROL, {uint64_t{1} << 63, 1, 64}).r, 1u);
  EXPECT_EQ(callN(Native::ROR, {1, 1, 32}).r, 0x80000000u);
  EXPECT_EQ(callN(Native::ROL, {0xFF01, 1, 8}).r, 0x02u);  // bits above the width are dropped
  EXPECT_EQ(callN(Native::ROR, {1, i(-1), 8}).r, 0x02u);   // (2^64 - 1) mod 8 = 7 positions
}

TEST(Natives, AssignLenCmpFind) {
  EXPECT_EQ(str(Native::STR_ASSIGN, {kA}, "hello"), "hello");
  EXPECT_EQ(str(Native::STR_ASSIGN, {kA}, "hello", "", 3), "hel");
  EXPECT_EQ(str(Native::STR_ASSIGN, {kA}, "hello", "", 0), "");
  EXPECT_EQ(callN(Native::STR_LEN, {kA}, {{kA, "hello"}}).r, 5u);
  EXPECT_EQ(callN(Native::STR_LEN, {kA}, {{kA, ""}}).r, 0u);
  auto cmp = [](std::string a, std::string b) { return static_cast<int64_t>(callN(Native::STR_CMP, {kA, kB}, {{kA, a}, {kB, b}}).r); };
  EXPECT_EQ(cmp("abc", "abc"), 0);
  EXPECT_EQ(cmp("abc", "abd"), -1);
  EXPECT_EQ(cmp("abd", "abc"), 1);
  EXPECT_EQ(cmp("ab", "abc"), -1);
  EXPECT_EQ(cmp("", ""), 0);
  EXPECT_EQ(cmp("\xff", "a"), 1);  // bytewise, unsigned
  auto find = [](std::string a, std::string b) { return callN(Native::STR_FIND, {kA, kB}, {{kA, a}, {kB, b}}).r; };
  EXPECT_EQ(find("abcabc", "ca"), 3u);
  EXPECT_EQ(find("abc", "abc"), 1u);
  EXPECT_EQ(find("abc", "x"), 0u);
  EXPECT_EQ(find("abc", ""), 0u);
  EXPECT_EQ(find("ab", "abc"), 0u);
}

TEST(Natives, LeftRightMid) {
  EXPECT_EQ(str(Native::STR_LEFT, {kA, 2}, "SUSI"), "SU");
  EXPECT_EQ(str(Native::STR_LEFT, {kA, 9}, "SUSI"), "SUSI");
  EXPECT_EQ(str(Native::STR_LEFT, {kA, i(-1)}, "SUSI"), "");
  EXPECT_EQ(str(Native::STR_LEFT, {kA, 4}, "SUSI", "", 3), "SUS");
  EXPECT_EQ(str(Native::STR_RIGHT, {kA, 3}, "SUSI"), "USI");
  EXPECT_EQ(str(Native::STR_RIGHT, {kA, 9}, "SUSI"), "SUSI");
  EXPECT_EQ(str(Native::STR_RIGHT, {kA, 0}, "SUSI"), "");
  EXPECT_EQ(str(Native::STR_MID, {kA, 2, 2}, "SUSI"), "US");
  EXPECT_EQ(str(Native::STR_MID, {kA, 9, 3}, "SUSI"), "SI");
  EXPECT_EQ(str(Native::STR_MID, {kA, 2, 4}, "SUSI"), "I");
  EXPECT_EQ(str(Native::STR_MID, {kA, 2, 5}, "SUSI"), "");
  EXPECT_EQ(str(Native::STR_MID, {kA, 2, 0}, "SUSI"), "");
  EXPECT_EQ(str(Native::STR_MID, {kA, 2, i(-3)}, "SUSI"), "");
  EXPECT_EQ(str(Native::STR_MID, {kA, i(-2), 1}, "SUSI"), "");
}

TEST(Natives, ConcatInsertDeleteReplace) {
  EXPECT_EQ(str(Native::STR_CONCAT, {kA, kB}, "AB", "CD"), "ABCD");
  EXPECT_EQ(str(Native::STR_CONCAT, {kA, kB}, "AB", "CD", 3), "ABC");
  EXPECT_EQ(str(Native::STR_INSERT, {kA, kB, 2}, "SUSI", "XY"), "SUXYSI");
  EXPECT_EQ(str(Native::STR_INSERT, {kA, kB, 0}, "SUSI", "XY"), "XYSUSI");
  EXPECT_EQ(str(Native::STR_INSERT, {kA, kB, 4}, "SUSI", "XY"), "SUSIXY");
  EXPECT_EQ(str(Native::STR_INSERT, {kA, kB, 99}, "SUSI", "XY"), "SUSIXY");
  EXPECT_EQ(str(Native::STR_INSERT, {kA, kB, i(-5)}, "SUSI", "XY"), "XYSUSI");
  EXPECT_EQ(str(Native::STR_INSERT, {kA, kB, 2}, "SUSI", "XY", 5), "SUXYS");
  EXPECT_EQ(str(Native::STR_DELETE, {kA, 2, 3}, "SUXYSI"), "SUSI");
  EXPECT_EQ(str(Native::STR_DELETE, {kA, 9, 3}, "SUXYSI"), "SU");
  EXPECT_EQ(str(Native::STR_DELETE, {kA, 2, 0}, "SUXYSI"), "SUXYSI");
  EXPECT_EQ(str(Native::STR_DELETE, {kA, 2, 7}, "SUXYSI"), "SUXYSI");
  EXPECT_EQ(str(Native::STR_DELETE, {kA, i(-2), 1}, "SUXYSI"), "SUXYSI");
  EXPECT_EQ(str(Native::STR_REPLACE, {kA, kB, 2, 3}, "SUXYSI", "ab"), "SUabSI");
  EXPECT_EQ(str(Native::STR_REPLACE, {kA, kB, 0, 1}, "SUSI", "ab"), "abSUSI");
  EXPECT_EQ(str(Native::STR_REPLACE, {kA, kB, 9, 3}, "SUSI", "ab"), "SUab");
  EXPECT_EQ(str(Native::STR_REPLACE, {kA, kB, 1, 0}, "SUSI", "ab"), "abUSI");
  EXPECT_EQ(str(Native::STR_REPLACE, {kA, kB, 1, 99}, "SUSI", "ab"), "SUSIab");
}

TEST(Natives, DestinationMayAliasSource) {
  // s := CONCAT(s, s) and s := INSERT(s, s, 1) with s at kDst.
  NativeResult r = callN(Native::STR_CONCAT, {kDst, 80, kDst, kDst}, {{kDst, "ab"}});
  EXPECT_EQ(r.dst, "abab");
  r = callN(Native::STR_INSERT, {kDst, 80, kDst, kDst, 1}, {{kDst, "xyz"}});
  EXPECT_EQ(r.dst, "xxyzyz");
  r = callN(Native::STR_MID, {kDst, 80, kDst, 2, 2}, {{kDst, "hello"}});
  EXPECT_EQ(r.dst, "el");
}

TEST(Natives, ToAndFromText) {
  EXPECT_EQ(str(Native::STR_FROM_I, {i(-42)}), "-42");
  EXPECT_EQ(str(Native::STR_FROM_I, {i(INT64_MIN)}), "-9223372036854775808");
  EXPECT_EQ(str(Native::STR_FROM_I, {12345}, "", "", 3), "123");
  EXPECT_EQ(str(Native::STR_FROM_U, {UINT64_MAX}), "18446744073709551615");
  EXPECT_EQ(str(Native::STR_FROM_REAL, {f(0.1f)}), "0.1");
  EXPECT_EQ(str(Native::STR_FROM_REAL, {f(2.0)}), "2.0");
  EXPECT_EQ(str(Native::STR_FROM_REAL, {f(1e20f)}), formatReal(1e20f));
  EXPECT_EQ(str(Native::STR_FROM_LREAL, {f(0.1)}), "0.1");
  EXPECT_EQ(str(Native::STR_FROM_LREAL, {f(-1.5e-300)}), formatLreal(-1.5e-300));
  EXPECT_EQ(str(Native::STR_FROM_LREAL, {f(NAN)}), formatLreal(NAN));
  for (int64_t ms : {int64_t{0}, int64_t{1500}, int64_t{-2000}, int64_t{90061001}, int64_t{INT32_MIN}, int64_t{60000}})
    EXPECT_EQ(str(Native::STR_FROM_TIME, {i(ms)}), formatTimeMs(ms)) << ms;
  EXPECT_EQ(str(Native::STR_FROM_TIME, {1500}, "", "", 4), "T#1s");
  EXPECT_EQ(str(Native::STR_FROM_BOOL, {1}), "TRUE");
  EXPECT_EQ(str(Native::STR_FROM_BOOL, {0}), "FALSE");
  EXPECT_EQ(str(Native::STR_FROM_BOOL, {0}, "", "", 2), "FA");
  auto toI = [](std::string s) { return static_cast<int64_t>(callN(Native::STR_TO_I, {kA}, {{kA, s}}).r); };
  EXPECT_EQ(toI("42"), 42);
  EXPECT_EQ(toI("  -17abc"), -17);
  EXPECT_EQ(toI("+5"), 5);
  EXPECT_EQ(toI("abc"), 0);
  EXPECT_EQ(toI(""), 0);
  EXPECT_EQ(toI("99999999999999999999"), INT64_MAX);
  EXPECT_EQ(toI("-99999999999999999999"), INT64_MIN);
  auto toF = [](std::string s) { return asF(callN(Native::STR_TO_F, {kA}, {{kA, s}}).r); };
  EXPECT_EQ(toF("1.5"), 1.5);
  EXPECT_EQ(toF(" -2E3xyz"), -2000.0);
  EXPECT_EQ(toF("+0.25"), 0.25);
  EXPECT_EQ(toF("abc"), 0.0);
}

// Runs a (dst, cap, ...) WSTRING native on ASCII texts; returns the destination text.
std::string wstr(Native n, std::vector<uint64_t> rest, std::string a = "", std::string b = "", uint64_t cap = 80) {
  std::vector<uint64_t> args = {kDst, cap};
  args.insert(args.end(), rest.begin(), rest.end());
  NativeResult r = callN(n, args, {{kA, wide(a)}, {kB, wide(b)}});
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.r, 0u);
  return r.wdst;
}

TEST(Natives, WideStrings) {
  EXPECT_EQ(wstr(Native::WSTR_ASSIGN, {kA}, "hello"), "hello");
  EXPECT_EQ(wstr(Native::WSTR_ASSIGN, {kA}, "hello", "", 2), "he");
  EXPECT_EQ(callN(Native::WSTR_LEN, {kA}, {{kA, wide("hello")}}).r, 5u);
  EXPECT_EQ(callN(Native::WSTR_LEN, {kA}, {{kA, ""}}).r, 0u);
  EXPECT_EQ(static_cast<int64_t>(callN(Native::WSTR_CMP, {kA, kB}, {{kA, wide("ab")}, {kB, wide("abc")}}).r), -1);
  EXPECT_EQ(callN(Native::WSTR_CMP, {kA, kB}, {{kA, wide("abc")}, {kB, wide("abc")}}).r, 0u);
  // 0x0100 > 0x00FF although its low byte is smaller: compared by code unit, not bytewise.
  EXPECT_EQ(callN(Native::WSTR_CMP, {kA, kB}, {{kA, std::string("\x00\x01", 2)}, {kB, std::string("\xff\x00", 2)}}).r, 1u);
  EXPECT_EQ(wstr(Native::WSTR_LEFT, {kA, 2}, "SUSI"), "SU");
  EXPECT_EQ(wstr(Native::WSTR_RIGHT, {kA, 3}, "SUSI"), "USI");
  EXPECT_EQ(wstr(Native::WSTR_MID, {kA, 2, 2}, "SUSI"), "US");
  EXPECT_EQ(wstr(Native::WSTR_MID, {kA, 2, 0}, "SUSI"), "");
  EXPECT_EQ(wstr(Native::WSTR_CONCAT, {kA, kB}, "AB", "CD"), "ABCD");
  EXPECT_EQ(wstr(Native::WSTR_CONCAT, {kA, kB}, "AB", "CD", 3), "ABC");
  EXPECT_EQ(wstr(Native::WSTR_INSERT, {kA, kB, 2}, "SUSI", "XY"), "SUXYSI");
  EXPECT_EQ(wstr(Native::WSTR_DELETE, {kA, 2, 3}, "SUXYSI"), "SUSI");
  EXPECT_EQ(wstr(Native::WSTR_REPLACE, {kA, kB, 2, 3}, "SUXYSI", "ab"), "SUabSI");
  EXPECT_EQ(callN(Native::WSTR_FIND, {kA, kB}, {{kA, wide("abcabc")}, {kB, wide("ca")}}).r, 3u);
  EXPECT_EQ(callN(Native::WSTR_FIND, {kA, kB}, {{kA, wide("abc")}, {kB, wide("x")}}).r, 0u);
  // Conversions.
  NativeResult r = callN(Native::WSTR_FROM_STR, {kDst, 80, kA}, {{kA, "xy\xe4"}});
  EXPECT_EQ(r.wdst, "xy\xe4");
  r = callN(Native::STR_FROM_WSTR, {kDst, 80, kA}, {{kA, wide("hi") + std::string("\x00\x01", 2)}});
  EXPECT_EQ(r.dst, "hi?");
  r = callN(Native::STR_FROM_WSTR, {kDst, 1, kA}, {{kA, wide("hello")}});
  EXPECT_EQ(r.dst, "h");
  // A wide destination needs 2 * (cap + 1) bytes.
  const uint64_t end = 1024 + 4096;
  EXPECT_FALSE(callN(Native::WSTR_ASSIGN, {end - 21, 10, kA}, {{kA, wide("a")}}).ok);
  EXPECT_TRUE(callN(Native::WSTR_ASSIGN, {end - 22, 10, kA}, {{kA, wide("a")}}).ok);
}

TEST(Natives, BadAddressesFault) {
  const uint64_t end = 1024 + 4096;
  struct Case { Native n; std::vector<uint64_t> args; };
  for (const Case& c : {Case{Native::STR_LEN, {0}}, Case{Native::STR_LEN, {end}}, Case{Native::STR_LEN, {i(-1)}},
                        Case{Native::STR_CMP, {kA, 15}}, Case{Native::STR_FIND, {end + 100, kA}},
                        Case{Native::STR_ASSIGN, {8, 10, kA}}, Case{Native::STR_ASSIGN, {end - 10, 10, kA}},
                        Case{Native::STR_ASSIGN, {kDst, UINT64_MAX, kA}}, Case{Native::STR_CONCAT, {kDst, 10, kA, 0}},
                        Case{Native::STR_FROM_I, {end - 1, 1, 5}}, Case{Native::STR_TO_F, {3}}}) {
    NativeResult r = callN(c.n, c.args, {{kA, "abc"}});
    EXPECT_FALSE(r.ok) << bc::nativeName(c.n);
    EXPECT_EQ(r.fault, FaultKind::InvalidPointer) << bc::nativeName(c.n);
  }
  // A destination that exactly fits: cap + 1 bytes up to the end of memory.
  NativeResult r = callN(Native::STR_ASSIGN, {end - 11, 10, kA}, {{kA, "abc"}});
  EXPECT_TRUE(r.ok);
}

TEST(Natives, UnterminatedSourceEndsAtMemoryEnd) {
  ModuleBuilder b;
  b.beginPou("MAIN", 6);
  b.emit(abx(Op::LDK, 2, b.constant(1024 + 4096 - 3)));
  b.emit(abx(Op::CALLN, 2, static_cast<uint32_t>(Native::STR_LEN)));
  b.emit(abx(Op::STA_64, 2, 16));
  b.emit(abc(Op::RET));
  vm::Machine vm(b.m);
  vm.coldStart();
  std::memset(vm.memory() + vm.memorySize() - 3, 'x', 3);
  ASSERT_TRUE(vm.run(0, 0));
  EXPECT_EQ(vm.memory()[16], 3);
}

}  // namespace
}  // namespace virtcom
