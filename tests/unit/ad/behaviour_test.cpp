// Each element of the diagram language against the Structured Text a controls engineer would
// write for it: the same pseudo-random (seeded) input sequence drives both programs for many
// scans, and every output must be identical after every scan; the diagram also runs as AOT machine
// code, which must give the interpreter's outputs.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "ad_fixture.hpp"

namespace virtcom::ad {
namespace {

struct Equivalence {
  const char* name;
  std::vector<std::string> inputs, outputs;
  std::string diagramBody;  // elements other than the port activities, and the arcs
  std::string stVars;       // extra VAR declarations of the ST program
  std::string stBody;
};

// Program P: every input and output is a port and an activity of the same name.
std::string diagramText(const Equivalence& c) {
  std::string text = "program P\n";
  for (const auto& name : c.inputs) text += "port " + name + " I\n";
  for (const auto& name : c.outputs) text += "port " + name + " O\n";
  text += "diagram D\n  start S\n";
  for (const auto& name : c.inputs) text += "  activity " + name + "\n";
  for (const auto& name : c.outputs) text += "  activity " + name + "\n";
  text += "  S -> " + c.inputs.front() + "\n";
  return text + c.diagramBody + "end_diagram\n";
}

std::string stText(const Equivalence& c) {
  std::string text = "PROGRAM P\nVAR\n";
  for (const auto& name : c.inputs) text += "  " + name + " : BOOL;\n";
  for (const auto& name : c.outputs) text += "  " + name + " : BOOL;\n";
  return text + c.stVars + "END_VAR\n" + c.stBody + "END_PROGRAM\n";
}

const Equivalence kCases[] = {
    {"NormalNotInNotOut", {"A", "B", "C"}, {"Y", "Z"},
     "  A -> Y\n  B ->| Y\n  C |-> Z\n  A ->| Z\n", "",
     "IF A THEN Y := TRUE; END_IF;\nIF B THEN Y := FALSE; END_IF;\nIF NOT C THEN Z := TRUE; END_IF;\n"
     "IF A THEN Z := FALSE; END_IF;\n"},
    {"OrJoin", {"A", "B", "C"}, {"Y"},
     "  or-join J\n  A -> J\n  B -> J\n  J -> Y\n  C ->| Y\n", "",
     "IF A OR B THEN Y := TRUE; END_IF;\nIF C THEN Y := FALSE; END_IF;\n"},
    {"AndJoinWithNotIn", {"A", "B", "C"}, {"Y"},
     "  and-join J\n  A -> J\n  B |-> J\n  J -> Y\n  C ->| Y\n", "",
     "IF A AND NOT B THEN Y := TRUE; END_IF;\nIF C THEN Y := FALSE; END_IF;\n"},
    {"AndSplitWithNotOut", {"A", "B"}, {"Y", "Z"},
     "  and-split K\n  and-split L\n  A -> K\n  K -> Y\n  K ->| Z\n  B -> L\n  L ->| Y\n  L -> Z\n", "",
     "IF A THEN Y := TRUE; Z := FALSE; END_IF;\nIF B THEN Y := FALSE; Z := TRUE; END_IF;\n"},
    {"Timers", {"A", "B", "C"}, {"Y", "Z", "W"},
     "  timer T1 TON T#50ms\n  timer T2 TOF T#30ms\n  timer T3 TP T#40ms\n"
     "  A -> T1\n  T1 -> Y\n  A -> T2\n  T2 -> Z\n  B -> T3\n  T3 -> W\n  C ->| Y\n  C ->| Z\n  C ->| W\n",
     "  T1 : TON;\n  T2 : TOF;\n  T3 : TP;\n",
     "T1(IN := A, PT := T#50ms);\nIF T1.Q THEN Y := TRUE; END_IF;\nT2(IN := A, PT := T#30ms);\n"
     "IF T2.Q THEN Z := TRUE; END_IF;\nT3(IN := B, PT := T#40ms);\nIF T3.Q THEN W := TRUE; END_IF;\n"
     "IF C THEN Y := FALSE; END_IF;\nIF C THEN Z := FALSE; END_IF;\nIF C THEN W := FALSE; END_IF;\n"},
    {"Counters", {"A", "B", "C"}, {"Y", "Z"},
     "  counter Up CTU 3\n  counter Down CTD 2\n"
     "  B ->| Up\n  A -> Up\n  Up -> Y\n  C ->| Y\n  C ->| Down\n  B -> Down\n  Down -> Z\n  A ->| Z\n",
     "  Up : CTU;\n  Down : CTD;\n",
     "Up(CU := A, RESET := B, PV := 3);\nIF Up.Q THEN Y := TRUE; END_IF;\nIF C THEN Y := FALSE; END_IF;\n"
     "Down(CD := B, LOAD := C, PV := 2);\nIF Down.Q THEN Z := TRUE; END_IF;\nIF A THEN Z := FALSE; END_IF;\n"},
    {"JoinPrecedentGroupK", {"C1", "L", "M", "R"}, {"Y"},
     "  or-join K\n  and-join J\n  C1 -> K\n  L -> K\n  K -> J\n  M -> J\n  J -> Y\n  R ->| Y\n", "",
     "IF (C1 OR L) AND M THEN Y := TRUE; END_IF;\nIF R THEN Y := FALSE; END_IF;\n"},
    {"SplitPrecedent", {"A", "B", "C"}, {"Y", "Z"},
     "  and-split Fork\n  and-join WithB\n  A -> Fork\n  Fork -> Y\n  Fork -> WithB\n  B -> WithB\n  WithB -> Z\n"
     "  C ->| Y\n  C ->| Z\n", "",
     "IF A THEN Y := TRUE; END_IF;\nIF A AND B THEN Z := TRUE; END_IF;\nIF C THEN Y := FALSE; END_IF;\n"
     "IF C THEN Z := FALSE; END_IF;\n"},
};

void PrintTo(const Equivalence& c, std::ostream* os) { *os << c.name; }

class Behaviour : public ::testing::TestWithParam<Equivalence> {};

using test::Side;
using test::start;

TEST_P(Behaviour, DiagramMatchesHandWrittenSt) {
  const Equivalence& c = GetParam();
  for (uint32_t seed : {1u, 2u, 3u}) {
    Side diagram, diagramAot, st;
    ASSERT_NO_FATAL_FAILURE(start(diagram, "case.ad", diagramText(c)));
    ASSERT_NO_FATAL_FAILURE(start(diagramAot, "case.ad", diagramText(c), true));
    ASSERT_NO_FATAL_FAILURE(start(st, "case.st", stText(c)));
    std::mt19937 rng(seed);
    std::vector<bool> inputs(c.inputs.size());
    for (int scan = 1; scan <= 400; ++scan) {
      for (size_t i = 0; i < inputs.size(); ++i) {
        if (rng() % 5 == 0) inputs[i] = !inputs[i];  // runs of a few scans, so timers elapse
        diagram.write(c.inputs[i], inputs[i]);
        diagramAot.write(c.inputs[i], inputs[i]);
        st.write(c.inputs[i], inputs[i]);
      }
      ASSERT_TRUE(diagram.runtime->tick()) << diagram.runtime->faultText();
      ASSERT_TRUE(diagramAot.runtime->tick()) << diagramAot.runtime->faultText();
      ASSERT_TRUE(st.runtime->tick()) << st.runtime->faultText();
      for (const auto& out : c.outputs) {
        ASSERT_EQ(diagram.read(out), st.read(out)) << out << " after scan " << scan << ", seed " << seed;
        ASSERT_EQ(diagramAot.read(out), diagram.read(out)) << out << " (AOT) after scan " << scan << ", seed " << seed;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Ad, Behaviour, ::testing::ValuesIn(kCases), [](const auto& info) { return std::string(info.param.name); });

TEST(Behaviour, OutputsActuallyChange) {
  // Guards the comparison above against two programs that never do anything.
  Side side;
  ASSERT_NO_FATAL_FAILURE(start(side, "case.ad", diagramText(kCases[0])));
  side.write("A", true);
  ASSERT_TRUE(side.runtime->tick());
  EXPECT_EQ(side.read("Y"), "TRUE");
  side.write("B", true);
  ASSERT_TRUE(side.runtime->tick());
  EXPECT_EQ(side.read("Y"), "FALSE");
}

}  // namespace
}  // namespace virtcom::ad
