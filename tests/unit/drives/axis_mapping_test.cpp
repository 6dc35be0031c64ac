// The declarative UNIVERSAL_AXIS <-> telegram mapping (docs/universal-axis.md, Mapping files): the
// bundled files load, pack/unpack produce the expected raw words and wire bytes, and every kind of mistake
// is reported at its file position.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "bytecode/module.hpp"
#include "cell/yaml_config.hpp"
#include "drives/axis_mapping.hpp"
#include "lang/st/compiler.hpp"

namespace fs = std::filesystem;
using namespace virtcom;
using namespace virtcom::drives;

namespace {

const fs::path kLib = fs::path(VIRTCOM_SOURCE_DIR) / "lib";

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Loaded {
  SourceManager sources;
  Diagnostics diags;
  std::optional<MappingSpec> spec;
  std::string rendered() const { return diags.render(sources); }
};

void load(Loaded& l, const std::string& path, const std::string& text) {
  ConfigNode root;
  if (cell::parseYaml(path, text, l.sources, l.diags, root)) l.spec = parseMapping(root, l.diags);
}

void loadBundled(Loaded& l, const std::string& name) {
  load(l, "lib/mappings/" + name, readFile(kLib / "mappings" / name));
  ASSERT_TRUE(l.spec) << l.rendered();
}

double& at(AxisSignalValues& v, AxisSignal s) { return v[static_cast<size_t>(s)]; }

std::vector<uint8_t> wire(const MappingRuntime& rt, const RawWords& words) {
  std::vector<uint8_t> image(imageBytes(rt.spec().telegram, Dir::ToDrive));
  rt.toWire(words, image);
  return image;
}

// Every Always_* pass-through TRUE, as the block outputs them by default.
void speedDefaults(AxisSignalValues& v) {
  for (AxisSignal s : {AxisSignal::Control_OFF2, AxisSignal::Control_OFF3, AxisSignal::Control_EnableOperation,
                       AxisSignal::Control_EnableRamp, AxisSignal::Control_ContinueRamp, AxisSignal::Control_EnableSpeed,
                       AxisSignal::Control_ControlFromPLC, AxisSignal::Control_EnablePos})
    at(v, s) = 1;
}

TEST(AxisMapping, BundledMappingsLoad) {
  size_t count = 0;
  for (const auto& entry : fs::directory_iterator(kLib / "mappings")) {
    if (entry.path().extension() != ".yaml") continue;
    Loaded l;
    load(l, entry.path().filename().string(), readFile(entry.path()));
    EXPECT_TRUE(l.spec) << entry.path() << "\n" << l.rendered();
    ++count;
  }
  EXPECT_EQ(count, 5u);
}

// E31 (telegram 1 side) and E1/E3: 0x047F + 8192 -> `04 7F 20 00`; the first frame keeps ON at 0.
TEST(AxisMapping, Telegram1PacksBigEndian) {
  Loaded l;
  loadBundled(l, "telegram1.yaml");
  MappingRuntime rt(*l.spec);
  AxisSignalValues v{};
  speedDefaults(v);
  at(v, AxisSignal::Control_Start) = 1;
  at(v, AxisSignal::Control_GoalSpeed_LU) = 8192;
  RawWords words{};
  rt.pack(v, words);
  EXPECT_EQ(words[0], 0x047Eu) << "ON must be 0 in the first frame (requires_zero_before_one)";
  rt.pack(v, words);
  EXPECT_EQ(words[0], 0x047Fu);
  EXPECT_EQ(wire(rt, words), (std::vector<uint8_t>{0x04, 0x7F, 0x20, 0x00}));
  at(v, AxisSignal::Control_SpeedDirection) = 1;
  rt.pack(v, words);
  EXPECT_EQ(words[0], 0x0C7Fu);
  EXPECT_EQ(words[1], 8192u);
}

TEST(AxisMapping, Telegram1UnpacksStatus) {
  Loaded l;
  loadBundled(l, "telegram1.yaml");
  MappingRuntime rt(*l.spec);
  RawWords in{};
  in[0] = 0x2F37 & ~0x4000u;  // S4, reverse
  in[1] = 0xE000;             // NIST_A = -8192
  AxisSignalValues v{};
  rt.unpack(in, v);
  EXPECT_EQ(at(v, AxisSignal::Status_Ready), 1);
  EXPECT_EQ(at(v, AxisSignal::Status_Blocked), 0);
  EXPECT_EQ(at(v, AxisSignal::Status_Direction), 0);
  EXPECT_EQ(at(v, AxisSignal::Status_ActualSpeed), -8192);
  // Configuration the mapping hands to the block.
  ASSERT_FALSE(l.spec->blockInputs.empty());
  EXPECT_EQ(l.spec->blockInputs[0].first, AxisSignal::Cfg_RefSpeed);
  EXPECT_EQ(l.spec->blockInputs[0].second, 1350);
}

// E31 (PowerFlex side) and E18/E19: LogicCommand 0x0012 + 1188 -> `12 00 A4 04`.
TEST(AxisMapping, Pf525PacksLittleEndianWithDirectionField) {
  Loaded l;
  loadBundled(l, "pf525.yaml");
  MappingRuntime rt(*l.spec);
  AxisSignalValues v{};
  at(v, AxisSignal::Control_AlarmReset) = 1;
  RawWords words{};
  rt.pack(v, words);
  EXPECT_EQ(words[0], 0x0008u) << "ClearFaults pulse";
  at(v, AxisSignal::Control_AlarmReset) = 0;
  at(v, AxisSignal::Control_Start) = 1;
  at(v, AxisSignal::Control_RockPositive) = 1;
  at(v, AxisSignal::Control_GoalSpeed_Hz) = 1188;
  rt.pack(v, words);
  EXPECT_EQ(words[0], 0x0012u);
  EXPECT_EQ(wire(rt, words), (std::vector<uint8_t>{0x12, 0x00, 0xA4, 0x04}));
  at(v, AxisSignal::Control_RockPositive) = 0;
  at(v, AxisSignal::Control_RockNegative) = 1;
  rt.pack(v, words);
  EXPECT_EQ(words[0], 0x0022u);
  at(v, AxisSignal::Control_GoalSpeed_Hz) = 9000;  // clamp [0, 6000]
  rt.pack(v, words);
  EXPECT_EQ(words[1], 6000u);

  const std::vector<uint8_t> image{0x0F, 0x01, 0xA4, 0x04};  // LogicStatus 0x010F, OutputFreq 1188
  RawWords in{};
  rt.fromWire(image, in);
  AxisSignalValues s{};
  rt.unpack(in, s);
  EXPECT_EQ(at(s, AxisSignal::Status_Ready), 1);
  EXPECT_EQ(at(s, AxisSignal::Status_AxisEnabled), 1);
  EXPECT_EQ(at(s, AxisSignal::Status_Direction), 1);
  EXPECT_EQ(at(s, AxisSignal::Status_SpeedReached), 1);
  EXPECT_EQ(at(s, AxisSignal::Status_Blocked), 0);
  EXPECT_EQ(at(s, AxisSignal::Status_ActualSpeed), 1188);
}

// E13/E23 raw words: MDI_TARPOS 70000 = `00 01 11 70`, OVERRIDE 50 % = 0x2000, acc 100 % = 0x4000,
// POS_STW1 0x8300; the master sign-of-life runs 1..15 and skips 0.
TEST(AxisMapping, Telegram111PacksPositioningWords) {
  Loaded l;
  loadBundled(l, "telegram111.yaml");
  MappingRuntime rt(*l.spec);
  AxisSignalValues v{};
  speedDefaults(v);
  at(v, AxisSignal::Control_noJOB_STOP) = 1;
  at(v, AxisSignal::Control_NOSTOP) = 1;
  at(v, AxisSignal::Control_RUN) = 1;
  at(v, AxisSignal::Control_PositioningMode) = 1;
  at(v, AxisSignal::Control_PositiveDir) = 1;
  at(v, AxisSignal::Control_GoalPosition) = 70000;
  at(v, AxisSignal::Control_SpeedPosition) = 100;
  at(v, AxisSignal::Control_OverridePosV) = 50;
  at(v, AxisSignal::Control_Acceleration) = 100;
  at(v, AxisSignal::Control_Deceleration) = 50;
  RawWords w{};
  rt.pack(v, w);
  EXPECT_EQ(w[0], 0x043Eu);
  EXPECT_EQ(w[1], 0x8300u);
  EXPECT_EQ(w[4], 0x2000u);
  EXPECT_EQ(w[5], 70000u);
  EXPECT_EQ(w[6], 100u);
  EXPECT_EQ(w[7], 0x4000u);
  EXPECT_EQ(w[8], 0x2000u);
  EXPECT_EQ(w[3] >> 12, 1u);
  const auto image = wire(rt, w);
  EXPECT_EQ(std::vector<uint8_t>(image.begin() + 10, image.begin() + 14), (std::vector<uint8_t>{0x00, 0x01, 0x11, 0x70}));
  at(v, AxisSignal::Control_Start) = 1;
  at(v, AxisSignal::Control_JobStart) = 1;
  rt.pack(v, w);
  EXPECT_EQ(w[0], 0x047Fu);
  rt.pack(v, w);
  EXPECT_EQ(w[0], 0x043Fu) << "JobStart is a one-tick pulse";
  for (int k = 4; k <= 16; ++k) rt.pack(v, w);
  EXPECT_EQ(w[3] >> 12, 1u) << "15 -> 1, 0 skipped";

  RawWords in{};
  in[4 + 1] = static_cast<uint32_t>(-123456);  // XIST_A
  in[6] = 0x20000000;                          // NIST_B
  in[2] = 0x0010;                              // POS_ZSW2.4
  in[3] = 0x7000;                              // ZSW2 sign-of-life 7
  AxisSignalValues s{};
  rt.unpack(in, s);
  EXPECT_EQ(at(s, AxisSignal::Status_ActualPosition), -123456);
  EXPECT_EQ(at(s, AxisSignal::Status_ActualSpeed), 0x20000000);
  EXPECT_EQ(at(s, AxisSignal::Status_PositiveDir), 1);
  EXPECT_EQ(at(s, AxisSignal::Status_SignOfLife), 7);
}

TEST(AxisMapping, Pf750SignsTheRealReference) {
  Loaded l;
  loadBundled(l, "pf750.yaml");
  MappingRuntime rt(*l.spec);
  AxisSignalValues v{};
  at(v, AxisSignal::Control_GoalSpeed_rpm) = 600;
  at(v, AxisSignal::Control_SpeedDirection) = 1;
  RawWords w{};
  rt.pack(v, w);
  EXPECT_EQ(realValue(w[1]), -600.0);
  RawWords in{};
  in[1] = rawFromReal(-600.0);
  AxisSignalValues s{};
  rt.unpack(in, s);
  EXPECT_EQ(at(s, AxisSignal::Status_ActualSpeed), -1000) << "600 rpm = 1000 x 0.01 Hz (thesis figure)";
}

// S7 byte.bit aliases convert with the formula of docs/drives.md (introduction): "STW1 0.2" = bit 10, "STW1 1.0" = bit 0.
// A mapped drive skips the wire image: toDrive()/fromDrive() give what writing the image in one
// byte order and decoding it in the telegram's gives, for either byte order of the mapping.
TEST(AxisMapping, ToDriveAndFromDriveMatchTheWireImage) {
  for (const char* name : {"telegram111.yaml", "telegram352.yaml", "pf525.yaml", "pf750.yaml"}) {
    Loaded l;
    loadBundled(l, name);
    for (const ByteOrder order : {ByteOrder::Big, ByteOrder::Little}) {
      MappingSpec spec = *l.spec;
      spec.order = order;
      MappingRuntime rt(spec);
      RawWords words{}, viaImage{}, direct{};
      for (size_t i = 0; i < words.size(); ++i) words[i] = 0x89ABCDEFu * static_cast<uint32_t>(i + 1);
      std::array<uint8_t, kMaxImageBytes> image{};
      rt.toWire(words, image);
      decode(spec.telegram, Dir::ToDrive, image, viaImage);
      rt.toDrive(words, direct, ~0u);
      EXPECT_EQ(direct, viaImage) << name;
      encode(spec.telegram, Dir::FromDrive, words, image);
      rt.fromWire(image, viaImage);
      direct = {};
      EXPECT_NE(rt.fromDrive(words, direct), 0u) << name;
      EXPECT_EQ(direct, viaImage) << name;
      EXPECT_EQ(rt.fromDrive(words, direct), 0u) << name << ": nothing changed the second time";
    }
  }
}

// A mapped drive packs again only when a Control_* value changed or repeatable() is false;
// otherwise advancing the sign-of-life must give what a full pack would.
TEST(AxisMapping, RepackingUnchangedValuesOnlyAdvancesTheSignOfLife) {
  Loaded l;
  loadBundled(l, "telegram111.yaml");
  MappingRuntime rt(*l.spec);
  AxisSignalValues v{};
  at(v, AxisSignal::Control_Start) = 1;
  at(v, AxisSignal::Control_JobStart) = 1;
  RawWords words{};
  rt.pack(v, words);
  EXPECT_FALSE(rt.repeatable()) << "the first frame holds Start at 0 and fires the JobStart pulse";
  rt.pack(v, words);
  EXPECT_TRUE(rt.repeatable());
  for (int tick = 0; tick < 20; ++tick) {
    MappingRuntime repacked = rt;
    RawWords full{};
    repacked.pack(v, full);
    EXPECT_NE(rt.advanceSignOfLife(words), 0u);
    EXPECT_EQ(words, full) << "tick " << tick;
  }
  at(v, AxisSignal::Control_AlarmReset) = 1;  // a pulse: the frame after it differs again
  rt.pack(v, words);
  EXPECT_FALSE(rt.repeatable());
}

TEST(AxisMapping, S7AliasAndBitNames) {
  Loaded l;
  load(l, "m.yaml",
       "telegram: siemens_std1\n"
       "outputs:\n"
       "  bits: {Control_Start: \"STW1 1.0\", Control_ControlFromPLC: \"STW1 0.2\", Control_OFF2: STW1.NoOff2}\n"
       "inputs:\n"
       "  bits: {Status_Blocked: ZSW1.FaultActive}\n");
  ASSERT_TRUE(l.spec) << l.rendered();
  MappingRuntime rt(*l.spec);
  AxisSignalValues v{};
  at(v, AxisSignal::Control_Start) = 1;
  at(v, AxisSignal::Control_ControlFromPLC) = 1;
  at(v, AxisSignal::Control_OFF2) = 1;
  RawWords w{};
  rt.pack(v, w);
  EXPECT_EQ(w[0], 0x0403u);
}

struct BadCase {
  const char* what;
  const char* yaml;
  const char* expected;  // substring of the rendered diagnostics, with its position
};

constexpr const char* kOk =
    "telegram: siemens_std1\n"
    "outputs:\n"
    "  bits: {Control_Start: STW1.0}\n"
    "inputs:\n"
    "  bits: {Status_Blocked: ZSW1.3}\n";

TEST(AxisMapping, ValidMinimalMapping) {
  Loaded l;
  load(l, "m.yaml", kOk);
  EXPECT_TRUE(l.spec) << l.rendered();
}

TEST(AxisMapping, ReportsMistakesWithPosition) {
  const BadCase cases[] = {
      {"bit mapped twice",
       "telegram: siemens_std1\noutputs:\n  bits: {Control_Start: STW1.0, Control_OFF2: STW1.0}\ninputs:\n  bits: {Status_Blocked: ZSW1.3}\n",
       "m.yaml:3:33: error[C010]: bit STW1.0 is written twice: by Control_Start and by Control_OFF2"},
      {"const over a mapped bit",
       "telegram: siemens_std1\noutputs:\n  bits: {Control_Start: STW1.0}\n  const: {STW1.0: 1}\ninputs:\n  bits: {Status_Blocked: ZSW1.3}\n",
       "m.yaml:4:11: error[C010]: bit STW1.0 is written twice: by Control_Start and by const STW1.0"},
      {"telegram given only as a YAML tag (fuzz_axis_mapping: rejected without a message)",
       "telegram: !b_pf525_velocity\noutputs:\n  bits: {Control_Start: STW1.0}\n",
       "m.yaml:1:11: error[C010]: unknown telegram ''"},
      {"missing required signal", "telegram: siemens_std1\noutputs:\n  bits: {Control_Start: STW1.0}\n",
       "m.yaml:1:1: error[C010]: missing required signal Status_Blocked"},
      {"no run command", "telegram: siemens_std1\ninputs:\n  bits: {Status_Blocked: ZSW1.3}\n",
       "m.yaml:1:1: error[C010]: missing required signal: the drive needs Control_Start or Control_Stop"},
      {"width mismatch: DINT into 16 bits",
       "telegram: siemens_std1\noutputs:\n  bits: {Control_Start: STW1.0}\n  Control_GoalPosition: {word: NSOLL_A}\n"
       "inputs:\n  bits: {Status_Blocked: ZSW1.3}\n",
       "m.yaml:4:32: error[C010]: width mismatch: Control_GoalPosition is DINT (32 bits) but NSOLL_A holds 16 bits"},
      {"width mismatch: BOOL to a word",
       "telegram: siemens_std1\noutputs:\n  Control_Start: {word: NSOLL_A}\ninputs:\n  bits: {Status_Blocked: ZSW1.3}\n",
       "m.yaml:3:25: error[C010]: width mismatch: Control_Start is BOOL"},
      {"width mismatch: code too wide",
       "telegram: ab_pf525_velocity\noutputs:\n  bits: {Control_Start: LogicCommand.1}\n"
       "  dir: {field: \"LogicCommand[4:5]\", encode: {Control_RockPositive: 0b101}}\ninputs:\n  bits: {Status_Blocked: LogicStatus.7}\n",
       "m.yaml:4:68: error[C010]: width mismatch: code 0b101 does not fit in 2 bits"},
      {"unknown telegram field",
       "telegram: siemens_std1\noutputs:\n  bits: {Control_Start: STW9.0}\ninputs:\n  bits: {Status_Blocked: ZSW1.3}\n",
       "m.yaml:3:25: error[C010]: unknown output word 'STW9' in telegram siemens_std1 (expected one of: STW1, NSOLL_A)"},
      {"unknown bit name",
       "telegram: siemens_std1\noutputs:\n  bits: {Control_Start: STW1.Go}\ninputs:\n  bits: {Status_Blocked: ZSW1.3}\n",
       "m.yaml:3:25: error[C010]: 'STW1.Go': expected WORD.bit (0..15 or a bit name of STW1)"},
      {"bit out of range",
       "telegram: siemens_std1\noutputs:\n  bits: {Control_Start: STW1.16}\ninputs:\n  bits: {Status_Blocked: ZSW1.3}\n",
       "m.yaml:3:25: error[C010]: 'STW1.16': expected WORD.bit"},
      {"unknown signal",
       "telegram: siemens_std1\noutputs:\n  bits: {Control_Strat: STW1.0}\ninputs:\n  bits: {Status_Blocked: ZSW1.3}\n",
       "m.yaml:3:10: error[C010]: 'Control_Strat' is not a Control_* signal of UNIVERSAL_AXIS"},
      {"signal mapped twice",
       "telegram: siemens_std1\noutputs:\n  bits: {Control_Start: STW1.0}\ninputs:\n  bits: {Status_Blocked: ZSW1.3}\n"
       "  Status_Blocked: {bit: ZSW1.6}\n",
       "m.yaml:6:3: error[C010]: Status_Blocked is mapped twice"},
      // was "unknown output word ''" (found by fuzz_axis_mapping's seed corpus)
      {"options inside the bits shorthand",
       "telegram: siemens_std1\noutputs:\n  bits: {Control_Start: {bit: STW1.0, invert: true}}\ninputs:\n  bits: {Status_Blocked: ZSW1.3}\n",
       "m.yaml:3:25: error[C010]: expected a word, bit or bit range of the telegram such as STW1.3"},
      {"unknown telegram", "telegram: siemens_std2\n", "m.yaml:1:11: error[C010]: unknown telegram 'siemens_std2'"},
      {"unknown key", "telegram: siemens_std1\noutputz: {}\n", "m.yaml:2:1: error[C011]: unknown key 'outputz'"},
      {"scale needs ref_speed",
       "telegram: siemens_std1\noutputs:\n  bits: {Control_Start: STW1.0}\n  Control_GoalSpeed_rpm: {word: NSOLL_A, scale: rpm_to_n2}\n"
       "inputs:\n  bits: {Status_Blocked: ZSW1.3}\n",
       "m.yaml:4:49: error[C010]: this scale needs `params: {ref_speed: <p2000 in rpm>}`"},
  };
  for (const BadCase& c : cases) {
    Loaded l;
    load(l, "m.yaml", c.yaml);
    EXPECT_FALSE(l.spec) << c.what;
    EXPECT_NE(l.rendered().find(c.expected), std::string::npos) << c.what << "\n" << l.rendered();
  }
}

// axis_signals.def and lib/universal_axis.st must agree on every name and type.
TEST(AxisMapping, SignalTableMatchesTheStLibrary) {
  std::vector<st::SourceInput> inputs = {
      {"universal_axis.st", readFile(kLib / "universal_axis.st")},
      {"main.st", "PROGRAM MAIN\nVAR ax : UNIVERSAL_AXIS; END_VAR\nax();\nEND_PROGRAM\n"}};
  SourceManager sources;
  Diagnostics diags;
  auto module = st::compileProgram(inputs, sources, diags);
  ASSERT_NE(module, nullptr) << diags.render(sources);
  for (const AxisSignalDef& s : axisSignals()) {
    auto ref = bc::resolveVariable(*module, "MAIN.ax." + std::string(s.name));
    ASSERT_TRUE(ref) << s.name << " is not a variable of UNIVERSAL_AXIS";
    const bc::TypeDesc& t = module->types[ref->type];
    EXPECT_EQ(t.kind, bc::TypeKind::Elementary) << s.name;
    EXPECT_EQ(t.elem, s.type) << s.name;
  }
}

}  // namespace
