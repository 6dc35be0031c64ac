// The ADS view of a compiled program: which symbols are listed, their addresses, TwinCAT type
// ids and layouts, read-only ranges, and paths resolved below the listed symbols.
#include "proto/ads/plc/module_symbols.hpp"

#include <gtest/gtest.h>

#include "lang/st/compiler.hpp"

namespace virtcom::proto::ads {
namespace {

const char* const kProgram = R"(
TYPE E_Mode : (Idle := 0, Busy := 2); END_TYPE
TYPE ST_P : STRUCT x : INT; s : STRING(10); END_STRUCT END_TYPE
FUNCTION_BLOCK FB_A
VAR_INPUT go : BOOL; END_VAR
VAR_OUTPUT n : DINT; END_VAR
END_FUNCTION_BLOCK
PROGRAM MAIN
VAR
  count : INT;
  p : ST_P;
  arr : ARRAY [1..3] OF REAL;
  mode : E_Mode;
  fb : FB_A;
  inBit AT %IX0.2 : BOOL;
  {attribute 'ads_readonly'}
  serial : DINT;
END_VAR
VAR CONSTANT
  kMax : INT := 5;
END_VAR
count := count + 1;
END_PROGRAM
)";

class ModuleSymbols : public ::testing::Test {
 protected:
  ModuleSymbols() {
    SourceManager sources;
    Diagnostics diags;
    module_ = st::compileProgram({{"main.st", kProgram}}, sources, diags);
  }
  const Symbol* listed(const SymbolTable& t, const std::string& name) {
    for (const Symbol& s : t.symbols())
      if (s.name == name) return &s;
    return nullptr;
  }
  std::unique_ptr<bc::Module> module_;
};

TEST_F(ModuleSymbols, ListsProgramVariablesWithTwinCatTypes) {
  ASSERT_TRUE(module_);
  SymbolTable t = buildSymbolTable(*module_);
  const Symbol* count = listed(t, "MAIN.count");
  ASSERT_TRUE(count);
  EXPECT_EQ(count->type, "INT");
  EXPECT_EQ(count->indexGroup, 0x4040u);
  EXPECT_EQ(count->size, 2u);
  EXPECT_EQ(count->adsType, adst::kInt16);
  auto ref = bc::resolveVariable(*module_, "MAIN.count");
  EXPECT_EQ(count->indexOffset, ref->address);
  EXPECT_EQ(listed(t, "MAIN.arr")->adsType, adst::kReal32);
  EXPECT_EQ(listed(t, "MAIN.p")->adsType, adst::kBigType);
  EXPECT_EQ(listed(t, "MAIN.fb")->type, "FB_A");
  EXPECT_EQ(listed(t, "MAIN.serial")->flags, kSymbolFlagReadOnly);
  EXPECT_EQ(listed(t, "MAIN.kMax")->flags, kSymbolFlagReadOnly);
  const Symbol* bit = listed(t, "MAIN.inBit");
  ASSERT_TRUE(bit);
  EXPECT_EQ(bit->indexGroup, 0xF021u);
  EXPECT_EQ(bit->indexOffset, 2u);
  EXPECT_EQ(bit->flags, kSymbolFlagBitValue);
}

TEST_F(ModuleSymbols, DescribesEveryTypeUsed) {
  ASSERT_TRUE(module_);
  SymbolTable t = buildSymbolTable(*module_);
  const DataType* p = t.findType("st_p");
  ASSERT_TRUE(p);
  ASSERT_EQ(p->members.size(), 2u);
  EXPECT_EQ(p->members[1].name, "s");
  EXPECT_EQ(p->members[1].type, "STRING(10)");
  EXPECT_EQ(p->members[1].size, 11u);
  const DataType* arr = t.findType("ARRAY [1..3] OF REAL");
  ASSERT_TRUE(arr);
  EXPECT_EQ(arr->baseType, "REAL");
  ASSERT_EQ(arr->dims.size(), 1u);
  EXPECT_EQ(arr->dims[0].lowerBound, 1);
  EXPECT_EQ(arr->dims[0].elementCount, 3u);
  const DataType* mode = t.findType("E_Mode");
  ASSERT_TRUE(mode);
  EXPECT_EQ(mode->flags, kTypeFlagDataType | kTypeFlagEnumInfos);
  EXPECT_EQ(mode->baseType, "INT");
  ASSERT_EQ(mode->enumerators.size(), 2u);
  EXPECT_EQ(mode->enumerators[1].value, 2);
  const DataType* fb = t.findType("FB_A");
  ASSERT_TRUE(fb);
  ASSERT_EQ(fb->members.size(), 2u);
  EXPECT_EQ(fb->members[0].name, "go");
  for (const char* base : {"INT", "REAL", "STRING(10)", "DINT", "BOOL"}) EXPECT_TRUE(t.findType(base)) << base;
}

TEST_F(ModuleSymbols, ResolvesPathsAndGuardsReadOnlyBytes) {
  ASSERT_TRUE(module_);
  SymbolTable t = buildSymbolTable(*module_);
  auto x = t.find("main.P.X");
  ASSERT_TRUE(x);
  EXPECT_EQ(x->indexOffset, listed(t, "MAIN.p")->indexOffset);
  EXPECT_EQ(t.find("MAIN.arr[2]")->indexOffset, listed(t, "MAIN.arr")->indexOffset + 4);
  EXPECT_EQ(t.find("MAIN.fb.n")->type, "DINT");
  EXPECT_FALSE(t.find("MAIN.arr[4]"));
  EXPECT_FALSE(t.find("MAIN.nothing"));
  EXPECT_TRUE(t.touchesReadOnly(listed(t, "MAIN.serial")->indexOffset, 1));
  EXPECT_FALSE(t.touchesReadOnly(listed(t, "MAIN.count")->indexOffset, 2));
  EXPECT_TRUE(t.touchesReadOnly(0, 1));  // the null guard
}

// SFC step flags are ADS symbols like any struct member (MAIN.Step.X / .T, TwinCAT's
// `MAIN.Step.x` form included); the hidden `__sfc_*` bookkeeping is not in the symbol upload.
TEST(ModuleSymbolsSfc, StepFlagsAreAddressableAndBookkeepingIsHidden) {
  const char* chart =
      "PROGRAM MAIN\nVAR go : BOOL; END_VAR\n"
      "INITIAL_STEP Idle: END_STEP\nSTEP Busy: END_STEP\n"
      "TRANSITION FROM Idle TO Busy := go; END_TRANSITION\n"
      "TRANSITION FROM Busy TO Idle := NOT go; END_TRANSITION\nEND_PROGRAM\n";
  SourceManager sources;
  Diagnostics diags;
  auto module = st::compileProgram({{"main.st", chart}}, sources, diags);
  ASSERT_TRUE(module) << diags.render(sources);
  SymbolTable t = buildSymbolTable(*module);
  std::vector<std::string> names;
  for (const Symbol& s : t.symbols()) names.push_back(s.name);
  EXPECT_EQ(names, (std::vector<std::string>{"MAIN.go", "MAIN.Idle", "MAIN.Busy"}));
  for (const char* step : {"MAIN.Idle", "MAIN.Busy"}) {
    SCOPED_TRACE(step);
    auto x = t.find(std::string(step) + ".X");
    ASSERT_TRUE(x);
    EXPECT_EQ(x->type, "BOOL");
    EXPECT_EQ(x->indexOffset, bc::resolveVariable(*module, std::string(step) + ".X")->address);
    auto time = t.find(std::string(step) + ".t");
    ASSERT_TRUE(time);
    EXPECT_EQ(time->type, "TIME");
    EXPECT_EQ(time->indexOffset, bc::resolveVariable(*module, std::string(step) + ".T")->address);
  }
  const DataType* stepType = t.findType("SFC_STEP");
  ASSERT_TRUE(stepType);
  ASSERT_EQ(stepType->members.size(), 2u);
}

}  // namespace
}  // namespace virtcom::proto::ads

namespace virtcom::proto::ads {
namespace {

// Issue 16: bit-located globals were missing from the table, and %M was 256 bytes whatever the
// program declared (Beckhoff's test project has ARRAY[0..1027] OF BYTE AT %MB0).
const char* const kLocatedGlobals = R"(
VAR_GLOBAL
  gStart AT %IX0.2 : BOOL;
  gLamp AT %QX1.7 : BOOL;
  gFlags AT %MB0 : ARRAY[0..1027] OF BYTE;
END_VAR
PROGRAM MAIN
VAR n : INT; END_VAR
n := n + 1;
END_PROGRAM
)";

TEST(ModuleSymbolsLocatedGlobals, BitGlobalsAreListedInTheirBitGroupAndTheMemoryAreaFitsTheProgram) {
  SourceManager sources;
  Diagnostics diags;
  auto module = st::compileProgram({{"main.st", kLocatedGlobals}}, sources, diags);
  ASSERT_TRUE(module) << diags.render(sources);
  SymbolTable t = buildSymbolTable(*module);
  auto start = t.find("gStart");
  ASSERT_TRUE(start);
  EXPECT_EQ(start->indexGroup, 0xF021u);
  EXPECT_EQ(start->indexOffset, 2u);
  EXPECT_EQ(start->size, 1u);
  EXPECT_EQ(start->flags & kSymbolFlagBitValue, kSymbolFlagBitValue);
  auto lamp = t.find("gLamp");
  ASSERT_TRUE(lamp);
  EXPECT_EQ(lamp->indexGroup, 0xF031u);
  EXPECT_EQ(lamp->indexOffset, 15u);
  auto flags = t.find("gFlags");
  ASSERT_TRUE(flags);
  EXPECT_EQ(flags->size, 1028u);
  EXPECT_GE(t.layout().memory.size, 1028u);
  EXPECT_EQ(t.layout().inputs.size, 256u);  // no larger need: the minimum
}

}  // namespace
}  // namespace virtcom::proto::ads
