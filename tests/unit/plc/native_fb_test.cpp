// The standard FBs the VM runs natively (CALLFB, bytecode/native_fbs.def): the compiler uses
// them for every standard FB of the prelude, and each native does exactly what the FB's ST
// body does, checked step by step against that body on random inputs.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "bytecode/module.hpp"
#include "core/diagnostics.hpp"
#include "core/source.hpp"
#include "lang/st/compiler.hpp"
#include "vm/machine.hpp"
#include "vm/natives.hpp"

namespace virtcom {
namespace {

constexpr const char* kProgram = R"(
PROGRAM MAIN
VAR
  ton1 : TON; tof1 : TOF; tp1 : TP; ctu1 : CTU; ctd1 : CTD; ctud1 : CTUD;
  rt : R_TRIG; ft : F_TRIG; sr1 : SR; rs1 : RS;
END_VAR
ton1(IN := TRUE, PT := T#1s);
tof1(IN := TRUE, PT := T#1s);
tp1(IN := TRUE, PT := T#1s);
ctu1(CU := TRUE, RESET := FALSE, PV := 3);
ctd1(CD := TRUE, LOAD := FALSE, PV := 3);
ctud1(CU := TRUE, CD := FALSE, RESET := FALSE, LOAD := FALSE, PV := 3);
rt(CLK := TRUE);
ft(CLK := FALSE);
sr1(SET1 := TRUE, RESET := FALSE);
rs1(SET := TRUE, RESET1 := FALSE);
END_PROGRAM
)";

std::unique_ptr<bc::Module> compileAll() {
  SourceManager sources;
  Diagnostics diags;
  auto module = st::compileProgram({{"main.st", kProgram}}, sources, diags);
  EXPECT_NE(module, nullptr) << diags.render(sources);
  return module;
}

const bc::PouInfo& pouNamed(const bc::Module& m, std::string_view name) {
  for (const auto& p : m.pous)
    if (p.name == name) return p;
  ADD_FAILURE() << "no pou " << name;
  return m.pous.front();
}

TEST(NativeFb, EveryStandardFbCallIsNative) {
  auto m = compileAll();
  ASSERT_NE(m, nullptr);
  const bc::PouInfo& main = pouNamed(*m, "MAIN");
  std::set<uint32_t> natives;
  for (uint32_t pc = main.codeStart; pc < main.codeStart + main.codeSize; ++pc) {
    EXPECT_NE(m->code[pc].op, bc::Op::CALL) << "pc " << pc;
    if (m->code[pc].op == bc::Op::CALLFB) natives.insert(m->code[pc].bx());
  }
  // If this fails, the prelude's layout of a standard FB no longer matches native_fbs.def.
  EXPECT_EQ(natives.size(), static_cast<size_t>(bc::NativeFb::Count_));
}

// Runs the native and the ST body of every standard FB side by side on the same random
// inputs (BOOL bytes 0, 1 and 2; time steps of 0..30 ms; counters pushed to their limits) and
// compares the whole instance and whether the task time was read after every call.
TEST(NativeFb, MatchesTheStBodyOnRandomInputs) {
  auto m = compileAll();
  ASSERT_NE(m, nullptr);
  std::mt19937 rng(12345);
  for (uint16_t k = 0; k < static_cast<uint16_t>(bc::NativeFb::Count_); ++k) {
    const auto fb = static_cast<bc::NativeFb>(k);
    const std::string name(bc::nativeFbName(fb));
    SCOPED_TRACE(name);
    uint32_t pou = 0;
    while (pou < m->pous.size() && m->pous[pou].name != name) ++pou;
    ASSERT_LT(pou, m->pous.size());
    const bc::TypeDesc& type = m->types[m->pous[pou].instanceType];
    const uint32_t address = m->programs.front().address;  // any writable instance-sized area
    vm::Machine st(*m), native(*m);
    ASSERT_TRUE(st.coldStart());
    ASSERT_TRUE(native.coldStart());
    // Both start from the FB's initial values: zero, except F_TRIG's M (TRUE).
    for (const bc::Field& f : type.fields) {
      std::memset(st.memory() + address + f.offset, 0, m->types[f.type].size);
      std::memset(native.memory() + address + f.offset, 0, m->types[f.type].size);
    }
    if (name == "F_TRIG") st.memory()[address + 2] = native.memory()[address + 2] = 1;
    int64_t now = 0;
    for (int step = 0; step < 3000; ++step) {
      now += static_cast<int64_t>(rng() % 31) * 1'000'000;
      for (const bc::Field& f : type.fields) {
        uint8_t* a = st.memory() + address + f.offset;
        uint8_t* b = native.memory() + address + f.offset;
        const ElemType e = m->types[f.type].elem;
        if (f.section == "VAR_INPUT") {
          if (e == ElemType::Bool) *a = *b = static_cast<uint8_t>(rng() % 5 == 0 ? 2 : rng() % 2);
          if (e == ElemType::Time) {
            const int32_t pt = static_cast<int32_t>(rng() % 120);
            std::memcpy(a, &pt, 4);
            std::memcpy(b, &pt, 4);
          }
          if (e == ElemType::Int) {
            const int16_t pv = static_cast<int16_t>(static_cast<int>(rng() % 9) - 3);
            std::memcpy(a, &pv, 2);
            std::memcpy(b, &pv, 2);
          }
        } else if (f.name == "CV" && rng() % 50 == 0) {
          const int16_t limits[] = {32766, 32767, -32767, -32768};
          const int16_t cv = limits[rng() % 4];
          std::memcpy(a, &cv, 2);
          std::memcpy(b, &cv, 2);
        }
      }
      st.setTaskTimeNs(now);
      const uint64_t readsBefore = st.timeReads();
      ASSERT_TRUE(st.run(pou, address)) << st.fault().describe(*m);
      const bool nativeRead = vm::kNativeFbs[k](native.memory() + address, now);
      ASSERT_EQ(nativeRead, st.timeReads() != readsBefore) << "step " << step;
      ASSERT_EQ(std::memcmp(st.memory() + address, native.memory() + address, type.size), 0) << "step " << step;
    }
  }
}

}  // namespace
}  // namespace virtcom
