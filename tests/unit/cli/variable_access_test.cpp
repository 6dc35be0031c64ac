// The variable access behind `virtcom exec --set/--print/--trace`: names as a user types them,
// resolved against a module the ST compiler built (the CLI's own option handling is covered
// end to end in tests/e2e).
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "bytecode/module.hpp"
#include "core/clock.hpp"
#include "core/diagnostics.hpp"
#include "core/source.hpp"
#include "lang/st/compiler.hpp"
#include "plc/runtime.hpp"

namespace virtcom {
namespace {

const char* const kGvl = R"st(VAR_GLOBAL
  total : DINT := 7;
END_VAR
)st";

const char* const kMain = R"st(TYPE Color : (Red, Green, Blue); END_TYPE

PROGRAM MAIN
VAR CONSTANT
  k : INT := 5;
END_VAR
VAR
  count : INT;
  w : WORD := 16#0009;
  arr : ARRAY[1..3] OF INT := [10, 20, 30];
  t : TON;
  c : Color := Green;
  name : STRING(5) := 'abc';
  button AT %IX0.2 : BOOL;
  period : TIME := T#1s500ms;
END_VAR
count := count + 1;
t(IN := TRUE, PT := T#1s);
END_PROGRAM
)st";

class VariableAccess : public ::testing::Test {
 protected:
  void SetUp() override {
    module_ = st::compileProgram({{"GVL.st", kGvl}, {"main.st", kMain}}, sources_, diags_);
    ASSERT_NE(module_, nullptr) << diags_.render(sources_);
    runtime_ = std::make_unique<plc::Runtime>(*module_, clock_);
    ASSERT_TRUE(runtime_->coldStart());
  }

  std::string print(const std::string& name) {
    auto ref = bc::resolveVariable(*module_, name);
    if (!ref) return "<unknown>";
    return bc::formatValue(*module_, *ref, runtime_->machine().memory());
  }
  std::string set(const std::string& name, const std::string& value) {
    auto ref = bc::resolveVariable(*module_, name);
    if (!ref) return "<unknown>";
    return bc::writeValueFromText(*module_, *ref, value, runtime_->machine().memory());
  }

  SourceManager sources_;
  Diagnostics diags_;
  std::unique_ptr<bc::Module> module_;
  VirtualClock clock_;
  std::unique_ptr<plc::Runtime> runtime_;
};

TEST_F(VariableAccess, ProgramMembersAndGlobalsByQualifiedName) {
  EXPECT_EQ(print("MAIN.count"), "0");
  EXPECT_EQ(print("GVL.total"), "7");
  EXPECT_EQ(print("MAIN.period"), "T#1s500ms");
  EXPECT_EQ(print("MAIN.name"), "'abc'");
  EXPECT_EQ(print("MAIN.c"), "Color#Green");
}

TEST_F(VariableAccess, NamesAreCaseInsensitive) {
  EXPECT_EQ(print("main.COUNT"), "0");
  EXPECT_EQ(print("gvl.Total"), "7");
}

TEST_F(VariableAccess, UnknownNamesDoNotResolve) {
  EXPECT_FALSE(bc::resolveVariable(*module_, "MAIN.nosuch"));
  EXPECT_FALSE(bc::resolveVariable(*module_, "count"));  // members need their program's name
  EXPECT_FALSE(bc::resolveVariable(*module_, "NOPRG.count"));
  EXPECT_FALSE(bc::resolveVariable(*module_, ""));
  EXPECT_FALSE(bc::resolveVariable(*module_, "MAIN."));
}

TEST_F(VariableAccess, ArrayElementsAndBounds) {
  EXPECT_EQ(print("MAIN.arr"), "[10, 20, 30]");
  EXPECT_EQ(print("MAIN.arr[1]"), "10");
  EXPECT_EQ(print("MAIN.arr[3]"), "30");
  EXPECT_FALSE(bc::resolveVariable(*module_, "MAIN.arr[0]"));
  EXPECT_FALSE(bc::resolveVariable(*module_, "MAIN.arr[4]"));
}

TEST_F(VariableAccess, FunctionBlockInstanceAndItsMembers) {
  ASSERT_TRUE(runtime_->tick());
  ASSERT_TRUE(runtime_->tick());
  EXPECT_EQ(print("MAIN.t"), "(IN := TRUE, PT := T#1s, Q := FALSE, ET := T#10ms)");  // hidden state not listed
  EXPECT_EQ(print("MAIN.t.ET"), "T#10ms");
  EXPECT_EQ(print("MAIN.t.q"), "FALSE");
}

TEST_F(VariableAccess, BitOfAnInteger) {
  EXPECT_EQ(print("MAIN.w.0"), "TRUE");
  EXPECT_EQ(print("MAIN.w.1"), "FALSE");
  EXPECT_EQ(print("MAIN.w.3"), "TRUE");
  ASSERT_EQ(set("MAIN.w.1", "TRUE"), "");
  EXPECT_EQ(print("MAIN.w"), "11");
  EXPECT_FALSE(bc::resolveVariable(*module_, "MAIN.w.16"));
}

TEST_F(VariableAccess, LocatedInputIsABitInTheInputArea) {
  auto ref = bc::resolveVariable(*module_, "MAIN.button");
  ASSERT_TRUE(ref);
  EXPECT_EQ(ref->bit, 2);
  EXPECT_GE(ref->address, module_->inputs.address);
  EXPECT_LT(ref->address, module_->inputs.address + module_->inputs.size);
  runtime_->inputImage()[ref->address - module_->inputs.address] = 0x04;
  ASSERT_TRUE(runtime_->tick());
  EXPECT_EQ(print("MAIN.button"), "TRUE");
}

TEST_F(VariableAccess, ConstantsAreMarkedReadOnly) {
  auto k = bc::resolveVariable(*module_, "MAIN.k");
  ASSERT_TRUE(k);
  EXPECT_TRUE(k->readOnly);
  auto count = bc::resolveVariable(*module_, "MAIN.count");
  ASSERT_TRUE(count);
  EXPECT_FALSE(count->readOnly);
}

TEST_F(VariableAccess, SetParsesIecLiteralsOfTheVariablesType) {
  EXPECT_EQ(set("MAIN.count", "16#7F"), "");
  EXPECT_EQ(print("MAIN.count"), "127");
  EXPECT_EQ(set("MAIN.count", "-5"), "");
  EXPECT_EQ(print("MAIN.count"), "-5");
  EXPECT_EQ(set("MAIN.period", "T#2m"), "");
  EXPECT_EQ(print("MAIN.period"), "T#2m");
  EXPECT_EQ(set("MAIN.c", "Blue"), "");
  EXPECT_EQ(print("MAIN.c"), "Color#Blue");
  EXPECT_EQ(set("MAIN.c", "Color#Red"), "");
  EXPECT_EQ(print("MAIN.c"), "Color#Red");
  EXPECT_EQ(set("MAIN.arr[2]", "99"), "");
  EXPECT_EQ(print("MAIN.arr"), "[10, 99, 30]");
  EXPECT_EQ(set("GVL.total", "1_000"), "");
  EXPECT_EQ(print("GVL.total"), "1000");
}

TEST_F(VariableAccess, SetStringIsTruncatedToItsCapacity) {
  EXPECT_EQ(set("MAIN.name", "'abcdefgh'"), "");
  EXPECT_EQ(print("MAIN.name"), "'abcde'");
}

TEST_F(VariableAccess, SetRejectsBadValuesWithAReason) {
  EXPECT_EQ(set("MAIN.count", "abc"), "invalid INT literal 'abc'");
  EXPECT_EQ(set("MAIN.count", "70000"), "value 70000 out of range for INT (-32768..32767)");
  EXPECT_NE(set("MAIN.c", "Purple"), "");
  EXPECT_NE(set("MAIN.period", "soon"), "");
  EXPECT_EQ(print("MAIN.count"), "0");  // a rejected value leaves the variable alone
}

TEST_F(VariableAccess, SetValuesAreSeenByTheNextScan) {
  ASSERT_EQ(set("MAIN.count", "41"), "");
  ASSERT_TRUE(runtime_->tick());
  EXPECT_EQ(print("MAIN.count"), "42");
}

}  // namespace
}  // namespace virtcom
