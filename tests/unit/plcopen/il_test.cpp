// IL bodies and FBD feedback through in-out variables (tests/golden/plcopen/beremiz_il_fbd.xml).
#include "plcopen_fixture.hpp"

namespace virtcom::plcopen::testing {
namespace {

TEST(Il, CounterWithLabelsCarriesTheCurrentResultAcrossAJump) {
  auto c = compileGolden("beremiz_il_fbd.xml");
  ASSERT_NE(c->module, nullptr) << c->rendered();
  Plc plc(*c->module);
  for (const char* expected : {"1", "2", "3"}) {
    plc.scan();
    EXPECT_EQ(plc.get("main.CntIL"), expected);
  }
  plc.set("main.Reset", "TRUE");
  plc.scan();
  EXPECT_EQ(plc.get("main.CntIL"), "17") << "JMPC to Restart, then LD StartValue falls through to Save";
  plc.set("main.Reset", "FALSE");
  plc.scan();
  EXPECT_EQ(plc.get("main.CntIL"), "18");
}

TEST(Fbd, FeedbackThroughAnInOutVariableReadsItsValueBeforeTheAssignment) {
  auto c = compileGolden("beremiz_il_fbd.xml");
  ASSERT_NE(c->module, nullptr) << c->rendered();
  Plc plc(*c->module);
  for (int scan = 0; scan < 6; ++scan) {
    plc.set("main.Reset", scan == 3 ? "TRUE" : "FALSE");
    plc.scan();
    EXPECT_EQ(plc.get("main.CntFBD"), plc.get("main.CntIL")) << "scan " << scan;
  }
  EXPECT_EQ(plc.get("main.CntFBD"), "19");
}

// One scan with random inputs a, b, c and raw (-100..199) given to main.forms, which main passes
// on to every twin; returns raw.
class RandomInputs {
 public:
  explicit RandomInputs(uint32_t seed) : seed_(seed) {}
  int scan(Plc& plc) {
    for (const char* input : {"main.forms.a", "main.forms.b", "main.forms.c"}) plc.set(input, next() & 0x10000 ? "TRUE" : "FALSE");
    const int raw = static_cast<int>(next() >> 16) % 300 - 100;
    plc.set("main.forms.raw", std::to_string(raw));
    plc.scan();
    return raw;
  }

 private:
  uint32_t next() { return seed_ = seed_ * 1103515245u + 12345u; }
  uint32_t seed_;
};

// Every output of the IL instance equals its ST twin's after `scan`.
void expectTwinsAgree(Plc& plc, const std::string& il, const std::string& st, std::initializer_list<const char*> outputs, int scan) {
  for (const char* out : outputs) ASSERT_EQ(plc.get(il + out), plc.get(st + out)) << out << " at scan " << scan;
}

// ILForms (IL) and ILFormsST (the same in ST) get the same inputs every scan.
TEST(Il, EveryInstructionFormMatchesItsStTwinScanByScan) {
  auto c = compileGolden("beremiz_il_fbd.xml");
  ASSERT_NE(c->module, nullptr) << c->rendered();
  Plc plc(*c->module);
  RandomInputs inputs(12345);
  int pulses = 0;
  for (int scan = 0; scan < 200; ++scan) {
    inputs.scan(plc);
    ASSERT_NO_FATAL_FAILURE(expectTwinsAgree(plc, "main.forms.", "main.twin.",
                                             {"both", "latched", "clamped", "doubled", "loops", "pulses", "counted", "flipped", "limited", "summed"},
                                             scan));
    pulses = std::stoi(plc.get("main.forms.pulses"));
  }
  EXPECT_EQ(plc.get("main.forms.loops"), "2");
  EXPECT_GT(std::stoi(plc.get("main.forms.counted")), 10) << "CU counter counted the rising edges of c (CLK edge)";
  EXPECT_GE(pulses, 35) << "the TON fires every 5th scan (30 ms, then one scan off); RETCN skips the count otherwise";
}

// ILMore and ILMoreST: the forms ILForms leaves out (ANDN(, XORN, STN, MUL/SUB/DIV/MOD, GE/LE/GT,
// CALC, CALCN, JMPCN, RETC), on the same inputs.
TEST(Il, TheConditionalAndNegatedFormsMatchTheirStTwinScanByScan) {
  auto c = compileGolden("beremiz_il_fbd.xml");
  ASSERT_NE(c->module, nullptr) << c->rendered();
  Plc plc(*c->module);
  RandomInputs inputs(777);
  int returnedEarly = 0;
  for (int scan = 0; scan < 300; ++scan) {
    const int raw = inputs.scan(plc);
    returnedEarly += raw > 90;
    ASSERT_NO_FATAL_FAILURE(expectTwinsAgree(plc, "main.more.", "main.moreTwin.",
                                             {"andNot", "xorNot", "notA", "arith", "inRange", "fromA", "fromNotB", "hits", "kept"}, scan));
  }
  EXPECT_EQ(std::stoi(plc.get("main.more.kept")), 300 - returnedEarly) << "RETC left the body when raw > 90";
  EXPECT_GT(returnedEarly, 0);
  EXPECT_GT(std::stoi(plc.get("main.more.fromA")), 5) << "CALC called countA";
  EXPECT_GT(std::stoi(plc.get("main.more.fromNotB")), 5) << "CALCN called countNotB";
  EXPECT_GT(std::stoi(plc.get("main.more.hits")), 50) << "JMPCN skipped the count only when c was FALSE";
}

struct IlError {
  const char* body;
  const char* message;
};

class IlErrors : public ::testing::TestWithParam<IlError> {};

TEST_P(IlErrors, AreReportedAtTheInstruction) {
  std::string xml = std::string(R"(<project xmlns="http://www.plcopen.org/xml/tc6_0201"><types><dataTypes/><pous>)"
                                R"(<pou name="P" pouType="program"><interface><localVars>)"
                                R"(<variable name="x"><type><INT/></type></variable><variable name="t"><type><derived name="TON"/></type></variable>)"
                                R"(</localVars></interface><body><IL><p><![CDATA[)") +
                    GetParam().body + "]]></p></IL></body></pou></pous></types></project>";
  auto c = compile({input("il.xml", xml)});
  EXPECT_EQ(c->module, nullptr);
  EXPECT_NE(c->rendered().find(GetParam().message), std::string::npos) << c->rendered();
}

INSTANTIATE_TEST_SUITE_P(
    Plcopen, IlErrors,
    ::testing::Values(IlError{"ST x", "il.xml:1:"}, IlError{"ST x", "X011"},
                      IlError{"LD x\nJMP Nowhere", "X010"},
                      IlError{"LD 1\nJMP L\nL: ST x", "type that does not follow"},
                      IlError{"LD x\nAND( x\nST x", "')' is missing"},
                      IlError{"LD TRUE\nIN x", "il.xml:2:4: error[E206]: 'x' is a variable of type INT, not a function block instance"},
                      IlError{"IN t", "IN reads the current result"},
                      IlError{"LD\n", "LD needs an operand"},
                      IlError{"LD x\nADD 1 ;\n", "E0"},
                      IlError{"L: LD x\nAND( x\nOR( 1\n)\n)\nJMPCN L\nCAL x(\nST x", "error"}));

}  // namespace
}  // namespace virtcom::plcopen::testing
