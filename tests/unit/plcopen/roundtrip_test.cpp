// import -> export -> import gives the same program: the second export equals the first (a fixed
// point), and both programs behave the same scan by scan.
#include "plcopen_fixture.hpp"

namespace virtcom::plcopen::testing {
namespace {

using Inputs = std::vector<std::pair<std::string, std::string>>;

// Runs both programs side by side and compares the named variables after every scan; each
// input (variable, value) is set in both before two more scans.
void expectSameBehaviour(const bc::Module& a, const bc::Module& b, const std::vector<std::string>& names, int scans,
                         const Inputs& inputs = {}) {
  Plc pa(a), pb(b);
  auto compareScans = [&](int count, const std::string& after) {
    for (int k = 0; k < count; ++k) {
      pa.scan();
      pb.scan();
      for (const auto& n : names) EXPECT_EQ(pa.get(n), pb.get(n)) << n << " after scan " << k << after;
    }
  };
  compareScans(scans, "");
  for (const auto& [name, value] : inputs) {
    pa.set(name, value);
    pb.set(name, value);
    compareScans(2, " after " + name + " := " + value);
  }
}

struct Case {
  std::string file;
  std::vector<std::string> watch;
  Inputs inputs;
};

class RoundTrip : public ::testing::TestWithParam<Case> {};

TEST_P(RoundTrip, ExportIsAFixedPointAndBehaviourIsKept) {
  const Case& tc = GetParam();
  auto original = compile({input(tc.file, readFile(kGoldenDir / tc.file))});
  ASSERT_NE(original->module, nullptr) << original->rendered();
  std::string first = exportOf({input(tc.file, readFile(kGoldenDir / tc.file))});
  ASSERT_FALSE(first.empty());
  auto reimported = compile({input("exported.xml", first)});
  ASSERT_NE(reimported->module, nullptr) << reimported->rendered() << first;
  EXPECT_EQ(exportOf({input("exported.xml", first)}), first);
  expectSameBehaviour(*original->module, *reimported->module, tc.watch, 8, tc.inputs);
}

INSTANTIATE_TEST_SUITE_P(
    Projects, RoundTrip,
    ::testing::Values(Case{"beremiz_ld.xml",
                           {"inst0.motor", "inst0.count", "inst0.pulse", "inst0.done", "inst0.z", "inst0.latch", "inst0.offPulse", "inst0.ret"},
                           {{"inst0.start", "TRUE"}, {"inst0.start", "FALSE"}, {"inst0.button", "TRUE"}, {"inst0.button", "FALSE"},
                            {"inst0.stop", "TRUE"}, {"inst0.rst", "TRUE"}, {"inst0.skip", "TRUE"}, {"inst0.zin", "TRUE"}}},
                      Case{"beremiz_fbd.xml",
                           {"prg.scaled", "prg.sum", "prg.osc.toggles", "prg.name", "prg.mode", "prg.big"},
                           {{"prg.raw", "60"}, {"prg.raw", "-3"}, {"prg.raw", "1000"}}},
                      Case{"mixed_languages.xml",
                           {"station.Idle.X", "station.Filling.X", "station.lamp", "station.ticks", "station.level"},
                           {{"station.go", "TRUE"}, {"station.go", "FALSE"}, {"station.go", "TRUE"}}},
                      Case{"codesys_st.xml", {"PLC_PRG.resets", "GVL.gScans", "PLC_PRG.axis.pos"}, {}},
                      // Wired conditions come back as named transitions with ST bodies, macro
                      // steps as their expanded steps.
                      Case{"sfc_conditions.xml",
                           {"seq.S0.X", "seq.S1.X", "seq.S2.X", "seq.S3.X", "seq.S4.X", "seq.S5.X", "seq.S6.X", "seq.S7.X", "seq.S8.X"},
                           {{"seq.start", "TRUE"}, {"seq.a", "TRUE"}, {"seq.level", "3"}, {"seq.ready", "TRUE"},
                            {"seq.b", "TRUE"}, {"seq.pressure", "6"}, {"seq.hold", "TRUE"}, {"seq.pulse", "TRUE"},
                            {"seq.hold", "FALSE"}}},
                      Case{"sfc_macro_step.xml",
                           {"tank.Idle.X", "tank.Fill__Open.X", "tank.Fill__Dose__Pump.X", "tank.Fill__Dose__Wait.X",
                            "tank.Fill__Close.X", "tank.Done.X", "tank.valve", "tank.pumping"},
                           {{"tank.go", "TRUE"}, {"tank.full", "TRUE"}, {"tank.dosed", "TRUE"}, {"tank.settled", "TRUE"},
                            {"tank.closed", "TRUE"}, {"tank.again", "TRUE"}}}),
    [](const auto& info) {
      std::string n = info.param.file.substr(0, info.param.file.find('.'));
      return n;
    });

TEST(RoundTripSt, StProgramExportsAndRunsTheSame) {
  std::string st =
      "TYPE Color : (Red, Green := 5, Blue); END_TYPE\n"
      "FUNCTION_BLOCK Acc\nVAR_INPUT inc : DINT := 1; END_VAR\nVAR_OUTPUT total : DINT; END_VAR\n"
      "METHOD Clear : BOOL\ntotal := 0;\nEND_METHOD\ntotal := total + inc;\nEND_FUNCTION_BLOCK\n"
      "PROGRAM MAIN\nVAR\n  acc : Acc;\n  c : Color := Color#Blue;\n  t : TIME := T#1m30s;\n"
      "  arr : ARRAY[1..3] OF INT := [2(7), -1];\n  s : STRING(20) := 'a$'b';\n  {attribute 'hide'}\n  k : INT;\n  r : LREAL := 0.1;\nEND_VAR\n"
      "acc(inc := 2);\nIF acc.total > 10 THEN acc.Clear(); END_IF\n"
      "FOR k := 1 TO 3 DO arr[k] := arr[k] + k * (2 - k) ** 2; END_FOR\n"
      "CASE k OF 1..3: r := r * 2.0; 4, 5: r := -r; ELSE r := r + 1.0; END_CASE\n"
      "END_PROGRAM\n";
  auto original = compile({input("main.st", st)});
  ASSERT_NE(original->module, nullptr) << original->rendered();
  std::string xml = exportOf({input("main.st", st)});
  EXPECT_NE(xml.find("<Attribute Name=\"hide\" Value=\"\" />"), std::string::npos) << xml;
  auto reimported = compile({input("main.xml", xml)});
  ASSERT_NE(reimported->module, nullptr) << reimported->rendered() << xml;
  EXPECT_EQ(exportOf({input("main.xml", xml)}), xml);
  expectSameBehaviour(*original->module, *reimported->module, {"MAIN.acc.total", "MAIN.arr", "MAIN.r", "MAIN.c", "MAIN.s", "MAIN.t"}, 8);
}

TEST(ExportLimits, ConstructsTc6CannotHoldAreReportedAtTheirLocation) {
  std::string st =
      "INTERFACE I_Run\nMETHOD Run : BOOL\nEND_METHOD\nEND_INTERFACE\n"
      "FUNCTION_BLOCK FB_A IMPLEMENTS I_Run\nVAR r : REFERENCE TO INT; END_VAR\n"
      "METHOD Run : BOOL\nRun := TRUE;\nEND_METHOD\nEND_FUNCTION_BLOCK\n"
      "PROGRAM MAIN\nVAR a : FB_A; END_VAR\na.Run();\nEND_PROGRAM\n"
      "FUNCTION_BLOCK FB_E\nVAR_INPUT go : BOOL R_EDGE; END_VAR\nEND_FUNCTION_BLOCK\n";
  SourceManager sources;
  Diagnostics diags;
  st::NodeId next = 0;
  auto units = st::parseInputs({input("main.st", st)}, sources, diags, next);
  ASSERT_FALSE(diags.hasErrors()) << diags.render(sources);
  std::vector<const st::CompilationUnit*> pointers{&units.front()};
  EXPECT_EQ(exportProject(pointers, {}, diags), "");
  std::string rendered = diags.render(sources);
  EXPECT_NE(rendered.find("main.st:1:11: error[X004]: INTERFACE 'I_Run' cannot be written"), std::string::npos) << rendered;
  EXPECT_NE(rendered.find("main.st:5:16: error[X004]: EXTENDS / IMPLEMENTS cannot be written"), std::string::npos) << rendered;
  EXPECT_NE(rendered.find("main.st:6:9: error[X004]: REFERENCE TO cannot be written"), std::string::npos) << rendered;
  // TC6 has no edge qualifier on variables.
  EXPECT_NE(rendered.find("main.st:16:21: error[X004]: R_EDGE / F_EDGE on an input cannot be written"), std::string::npos)
      << rendered;
}

}  // namespace
}  // namespace virtcom::plcopen::testing
