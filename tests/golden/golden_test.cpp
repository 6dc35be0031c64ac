// Golden tests: every tests/golden/st/**.st file (or folder with main.st) is compiled and run as
// its header comments say (see tests/golden/st/README.md). Diagnostics are also compared with a
// `.diag` file next to the test; VIRTCOM_UPDATE_GOLDEN=1 rewrites those files for review.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <thread>

#include "aot/compile.hpp"
#include "bytecode/module.hpp"
#include "core/clock.hpp"
#include "lang/sfc/step_monitor.hpp"
#include "lang/st/compiler.hpp"
#include "plc/runtime.hpp"

namespace fs = std::filesystem;
using namespace virtcom;

namespace {

const fs::path kRoot = fs::path(VIRTCOM_SOURCE_DIR) / "tests" / "golden" / "st";

struct GoldenCase {
  std::string name;                 // relative path, e.g. fbs/ton_done
  std::vector<fs::path> files;      // compiled together
  fs::path headerFile;              // file carrying the headers
};

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<GoldenCase> discover() {
  std::vector<GoldenCase> cases;
  if (!fs::exists(kRoot)) return cases;
  std::set<fs::path> folderTests;
  for (const auto& entry : fs::recursive_directory_iterator(kRoot))
    if (entry.is_regular_file() && entry.path().filename() == "main.st") folderTests.insert(entry.path().parent_path());
  for (const auto& entry : fs::recursive_directory_iterator(kRoot)) {
    if (!entry.is_regular_file() || entry.path().extension() != ".st") continue;
    fs::path dir = entry.path().parent_path();
    if (folderTests.count(dir)) continue;
    GoldenCase c;
    c.name = fs::relative(entry.path(), kRoot).replace_extension("").string();
    c.files = {entry.path()};
    c.headerFile = entry.path();
    cases.push_back(c);
  }
  for (const auto& dir : folderTests) {
    GoldenCase c;
    c.name = fs::relative(dir, kRoot).string();
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.path().extension() == ".st") c.files.push_back(entry.path());
    std::sort(c.files.begin(), c.files.end());
    c.headerFile = dir / "main.st";
    cases.push_back(c);
  }
  std::sort(cases.begin(), cases.end(), [](const GoldenCase& a, const GoldenCase& b) { return a.name < b.name; });
  return cases;
}

struct Header {
  int64_t cycles = 1;
  std::string cycleTime;
  std::vector<std::string> sets;
  std::vector<std::string> libs;  // lib/ files compiled with the test
  std::vector<std::pair<std::string, std::string>> checks;
  // Per-scan expectations, scans counted from 1: CHECK-AT, CHECK-BITS, CHECK-STEPS.
  std::map<int64_t, std::vector<std::pair<std::string, std::string>>> checksAt;
  std::vector<std::pair<std::string, std::string>> bits;  // BOOL variable, one 0/1 per scan
  std::map<int64_t, std::string> stepsAt;                  // active SFC steps after the scan
  std::string fault;
  std::set<uint32_t> errorLines, warningLines;
  bool expectErrors = false;
};

std::string trim(std::string s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  size_t i = 0;
  while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
  return s.substr(i);
}

Header parseHeader(const std::string& text) {
  Header h;
  std::stringstream ss(text);
  std::string line;
  while (std::getline(ss, line)) {
    line = trim(line);
    auto take = [&](const char* tag, std::string& rest) {
      std::string t = std::string("// ") + tag;
      if (line.rfind(t, 0) != 0) return false;
      rest = trim(line.substr(t.size()));
      return true;
    };
    std::string rest;
    if (take("RUN:", rest)) {
      std::stringstream rs(rest);
      std::string kv;
      while (rs >> kv) {
        if (kv.rfind("cycles=", 0) == 0) h.cycles = std::stoll(kv.substr(7));
        else if (kv.rfind("cycle-time=", 0) == 0) h.cycleTime = kv.substr(11);
        else if (kv.rfind("set=", 0) == 0) h.sets.push_back(kv.substr(4));
      }
    } else if (take("LIB:", rest)) {
      h.libs.push_back(rest);
    } else if (take("CHECK-FAULT:", rest)) {
      h.fault = rest;
    } else if (take("CHECK-AT:", rest)) {
      size_t space = rest.find(' ');
      auto eq = rest.find(" = ");
      if (space != std::string::npos && eq != std::string::npos)
        h.checksAt[std::stoll(rest.substr(0, space))].push_back(
            {trim(rest.substr(space, eq - space)), trim(rest.substr(eq + 3))});
    } else if (take("CHECK-BITS:", rest)) {
      auto eq = rest.find(" = ");
      if (eq != std::string::npos) h.bits.push_back({trim(rest.substr(0, eq)), trim(rest.substr(eq + 3))});
    } else if (take("CHECK-STEPS:", rest)) {
      size_t space = rest.find(' ');
      h.stepsAt[std::stoll(rest.substr(0, space))] = space == std::string::npos ? "" : trim(rest.substr(space));
    } else if (take("CHECK:", rest)) {
      auto eq = rest.find(" = ");
      if (eq != std::string::npos) h.checks.push_back({trim(rest.substr(0, eq)), trim(rest.substr(eq + 3))});
    } else if (take("EXPECT-ERROR:", rest)) {
      h.expectErrors = true;
      h.errorLines.insert(static_cast<uint32_t>(std::stoul(rest)));
    } else if (take("EXPECT-WARNING:", rest)) {
      h.warningLines.insert(static_cast<uint32_t>(std::stoul(rest)));
    }
  }
  return h;
}

int64_t parseCycleTimeNs(const std::string& s) {
  if (s.empty()) return 10'000'000;
  size_t i = 0;
  while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
  int64_t n = std::stoll(s.substr(0, i));
  std::string unit = s.substr(i);
  if (unit == "ms") return n * 1'000'000;
  if (unit == "us") return n * 1'000;
  if (unit == "s") return n * 1'000'000'000;
  return n * 1'000'000;
}

// The per-scan expectations of `scan`; CHECK-BITS values are collected into `bitsSeen`.
void checkScan(const bc::Module& module, const Header& h, int64_t scan, const std::vector<sfc::StepVariable>& steps,
               const uint8_t* memory, std::map<std::string, std::string>& bitsSeen) {
  auto value = [&](const std::string& name) {
    auto ref = bc::resolveVariable(module, name);
    return ref ? bc::formatValue(module, *ref, memory) : "<unknown variable " + name + ">";
  };
  if (auto it = h.checksAt.find(scan); it != h.checksAt.end()) {
    for (const auto& [name, expected] : it->second) EXPECT_EQ(value(name), expected) << name << " after scan " << scan;
  }
  for (const auto& [name, expected] : h.bits)
    if (static_cast<int64_t>(expected.size()) >= scan) bitsSeen[name] += value(name) == "TRUE" ? '1' : '0';
  if (auto it = h.stepsAt.find(scan); it != h.stepsAt.end()) {
    std::string active;
    sfc::formatActiveSteps(steps, memory, active);
    EXPECT_EQ(active, it->second) << "active steps after scan " << scan;
  }
}

void PrintTo(const GoldenCase& c, std::ostream* os) { *os << c.name; }

// The case's files and its LIB: files, compiled together. Null on compile errors.
std::unique_ptr<bc::Module> compileCase(const GoldenCase& c, const Header& h, SourceManager& sources, Diagnostics& diags,
                                        st::CompileOptions options = {}) {
  std::vector<st::SourceInput> inputs;
  for (const auto& f : c.files) inputs.push_back({fs::relative(f, kRoot).string(), readFile(f)});
  for (const auto& lib : h.libs) {
    const fs::path libFile = fs::path(VIRTCOM_SOURCE_DIR) / "lib" / lib;
    if (!fs::exists(libFile)) {
      ADD_FAILURE() << "LIB: " << libFile << " does not exist";
      return nullptr;
    }
    inputs.push_back({"lib/" + lib, readFile(libFile)});
  }
  return st::compileProgram(inputs, sources, diags, options);
}

void setCycleTime(bc::Module& module, const Header& h) {
  for (auto& t : module.tasks)
    if (t.isDefault) t.intervalNs = parseCycleTimeNs(h.cycleTime);
}

// The case's module compiled by src/aot, cached in the build tree.
aot::CompileResult compileAot(const bc::Module& module) {
  aot::CompileOptions aotOptions;
  aotOptions.cacheDir = VIRTCOM_AOT_TEST_CACHE;
  return aot::compileModule(module, aotOptions);
}

plc::RuntimeOptions runtimeOptions() {
  plc::RuntimeOptions options;
  options.instructionBudget = 2'000'000;
  return options;
}

// The header's set= presets, written into a cold-started image.
void applySets(const bc::Module& module, const Header& h, uint8_t* memory) {
  for (const auto& s : h.sets) {
    auto eq = s.find('=');
    auto ref = bc::resolveVariable(module, s.substr(0, eq));
    ASSERT_TRUE(ref) << "unknown variable in set=" << s;
    ASSERT_EQ(bc::writeValueFromText(module, *ref, s.substr(eq + 1), memory), "");
  }
}

class Golden : public ::testing::TestWithParam<GoldenCase> {};

TEST_P(Golden, Run) {
  const GoldenCase& c = GetParam();
  Header h = parseHeader(readFile(c.headerFile));
  SourceManager sources;
  Diagnostics diags;
  auto module = compileCase(c, h, sources, diags);
  std::string rendered = diags.render(sources);

  uint32_t headerFileId = 0;
  for (uint32_t i = 0; i < sources.fileCount(); ++i)
    if (sources.path(i) == fs::relative(c.headerFile, kRoot).string()) headerFileId = i;
  std::set<uint32_t> errors, warnings;
  for (const auto& d : diags.all()) {
    if (d.loc.fileId != headerFileId) continue;
    if (d.severity == Severity::Error) errors.insert(d.loc.line);
    if (d.severity == Severity::Warning) warnings.insert(d.loc.line);
  }
  if (h.expectErrors || !h.warningLines.empty()) {
    fs::path diagFile = fs::path(c.headerFile).replace_extension(".diag");
    if (c.headerFile.filename() == "main.st") diagFile = c.headerFile.parent_path() / "expected.diag";
    if (std::getenv("VIRTCOM_UPDATE_GOLDEN")) {
      std::ofstream(diagFile, std::ios::binary) << rendered;
    } else if (fs::exists(diagFile)) {
      EXPECT_EQ(readFile(diagFile), rendered) << "diagnostics differ from " << diagFile
                                              << " (VIRTCOM_UPDATE_GOLDEN=1 rewrites it)";
    } else {
      ADD_FAILURE() << "missing golden diagnostics " << diagFile << "; run with VIRTCOM_UPDATE_GOLDEN=1 and review it";
    }
  }
  if (h.expectErrors) {
    EXPECT_TRUE(module == nullptr) << "expected compile errors";
    EXPECT_EQ(errors, h.errorLines) << rendered;
    return;
  }
  ASSERT_NE(module, nullptr) << rendered;
  EXPECT_EQ(warnings, h.warningLines) << rendered;

  setCycleTime(*module, h);
  VirtualClock clock;
  plc::Runtime runtime(*module, clock, runtimeOptions());
  ASSERT_TRUE(runtime.coldStart()) << runtime.faultText();
  applySets(*module, h, runtime.machine().memory());
  bool faulted = false;
  std::vector<sfc::StepVariable> steps = sfc::findSteps(*module);
  std::map<std::string, std::string> bitsSeen;
  for (int64_t k = 0; k < h.cycles; ++k) {
    if (!runtime.tick()) {
      faulted = true;
      break;
    }
    checkScan(*module, h, k + 1, steps, runtime.machine().memory(), bitsSeen);
  }
  for (const auto& [name, expected] : h.bits) EXPECT_EQ(bitsSeen[name], expected) << name << " scan by scan";
  // The program ends as `exec` ends it: FB_exit runs (nothing after a fault), then CHECK.
  faulted = !runtime.exit() || faulted;
  if (!h.fault.empty()) {
    ASSERT_TRUE(faulted) << "expected a runtime fault containing '" << h.fault << "'";
    EXPECT_NE(runtime.faultText().find(h.fault), std::string::npos) << runtime.faultText();
  } else {
    ASSERT_FALSE(faulted) << runtime.faultText();
  }
  for (const auto& [name, expected] : h.checks) {
    auto ref = bc::resolveVariable(*module, name);
    if (!ref) {
      ADD_FAILURE() << "unknown variable " << name;
      continue;
    }
    EXPECT_EQ(bc::formatValue(*module, *ref, runtime.machine().memory()), expected) << name;
  }
}

// The AOT backend (src/aot) against the interpreter: every program that runs gives the same
// whole memory image (stack included) after every scan, and faults at the same scan with the
// same report (kind, file:line:col, call stack).
TEST_P(Golden, AotMatchesInterpreter) {
  const GoldenCase& c = GetParam();
  Header h = parseHeader(readFile(c.headerFile));
  if (h.expectErrors) GTEST_SKIP() << "does not compile";
  SourceManager sources;
  Diagnostics diags;
  auto module = compileCase(c, h, sources, diags);
  ASSERT_NE(module, nullptr) << diags.render(sources);
  setCycleTime(*module, h);
  const aot::CompileResult compiled = compileAot(*module);
  ASSERT_TRUE(compiled.code) << compiled.error;

  VirtualClock interpClock, aotClock;
  plc::Runtime interp(*module, interpClock, runtimeOptions()), native(*module, aotClock, runtimeOptions());
  native.machine().useCompiled(compiled.code);
  const bool started = interp.coldStart();
  ASSERT_EQ(native.coldStart(), started) << native.faultText();
  const uint32_t size = interp.machine().memorySize();
  const auto sameImage = [&](int64_t scan) {
    const uint8_t* a = interp.machine().memory();
    const uint8_t* b = native.machine().memory();
    const auto diff = std::mismatch(a, a + size, b);
    EXPECT_EQ(diff.first, a + size) << "memory differs at address " << (diff.first - a) << " after scan " << scan;
    return diff.first == a + size;
  };
  ASSERT_TRUE(sameImage(0));
  applySets(*module, h, interp.machine().memory());
  applySets(*module, h, native.machine().memory());
  for (int64_t k = 1; started && k <= h.cycles; ++k) {
    const bool ran = interp.tick();
    ASSERT_EQ(native.tick(), ran) << "scan " << k << ": " << interp.faultText() << " / " << native.faultText();
    ASSERT_TRUE(sameImage(k));
    if (!ran) break;
  }
  ASSERT_EQ(native.exit(), interp.exit()) << interp.faultText() << " / " << native.faultText();
  ASSERT_TRUE(sameImage(h.cycles + 1));
  EXPECT_EQ(native.faultText(), interp.faultText());
  EXPECT_EQ(native.machine().timeReads(), interp.machine().timeReads());
}

// Runs `module` on a runtime that stays on the interpreter and, side by side, on one that
// tiers up through `handoff` (published by the caller, before or while it runs): the whole
// memory image must be identical after every scan, the fault report and time reads at the end,
// and both skip the same repeated scans (the switch never makes a repeat look changed).
// Returns the tiered runtime's statistics.
plc::TierStats expectTieringInvisible(const bc::Module& module, const Header& h,
                                      std::shared_ptr<vm::CompiledHandoff> handoff) {
  plc::RuntimeOptions options = runtimeOptions();
  options.skipRepeatedScans = true;
  VirtualClock interpClock, tieredClock;
  plc::Runtime interp(module, interpClock, options), tiered(module, tieredClock, options);
  tiered.switchToCompiledWhenReady(std::move(handoff));
  const bool started = interp.coldStart();
  EXPECT_EQ(tiered.coldStart(), started);
  applySets(module, h, interp.machine().memory());
  applySets(module, h, tiered.machine().memory());
  const uint32_t size = interp.machine().memorySize();
  for (int64_t k = 1; started && k <= h.cycles; ++k) {
    const bool ran = interp.tick();
    EXPECT_EQ(tiered.tick(), ran) << "scan " << k;
    const uint8_t* a = interp.machine().memory();
    const auto diff = std::mismatch(a, a + size, tiered.machine().memory());
    if (diff.first != a + size) {
      ADD_FAILURE() << "memory differs at address " << (diff.first - a) << " after scan " << k << " (switched after "
                    << tiered.tierStats().interpScans << " interpreted scans)";
      break;
    }
    if (!ran) break;
  }
  EXPECT_EQ(tiered.faultText(), interp.faultText());
  EXPECT_EQ(tiered.machine().timeReads(), interp.machine().timeReads());
  for (size_t t = 0; t < module.tasks.size(); ++t) {
    EXPECT_EQ(tiered.stats(t).scans, interp.stats(t).scans);
    EXPECT_EQ(tiered.stats(t).skippedScans, interp.stats(t).skippedScans);
  }
  return tiered.tierStats();
}

// Tiered execution (`--backend auto`, docs/performance.md): the switch from the interpreter to
// the AOT code between two scans is invisible, at whatever scan it happens. Each case switches
// at scan 0 (before the first), at two scans drawn from a generator seeded with the case's name
// (reproducible, different per case) and once at whatever scan a real background thread's
// publication lands on.
TEST_P(Golden, TierSwitchIsInvisible) {
  const GoldenCase& c = GetParam();
  Header h = parseHeader(readFile(c.headerFile));
  if (h.expectErrors) GTEST_SKIP() << "does not compile";
  SourceManager sources;
  Diagnostics diags;
  auto module = compileCase(c, h, sources, diags);
  ASSERT_NE(module, nullptr) << diags.render(sources);
  setCycleTime(*module, h);
  const aot::CompileResult compiled = compileAot(*module);
  ASSERT_TRUE(compiled.code) << compiled.error;

  std::mt19937 rng(static_cast<uint32_t>(std::hash<std::string>{}(c.name)));
  const uint64_t cycles = static_cast<uint64_t>(std::max<int64_t>(h.cycles, 1));
  for (uint64_t at : {uint64_t{0}, rng() % cycles, rng() % cycles}) {
    SCOPED_TRACE("switch after " + std::to_string(at) + " interpreted scans");
    auto handoff = std::make_shared<vm::CompiledHandoff>();
    handoff->holdUntilScan(at);
    handoff->publish(compiled.code);
    const plc::TierStats stats = expectTieringInvisible(*module, h, handoff);
    // Scans run only until a fault; the switch is exactly where it was asked whenever the run got there.
    if (stats.interpScans + stats.compiledScans > at) {
      EXPECT_EQ(stats.interpScans, at);
      EXPECT_GE(stats.switchedAtNs, 0);
    }
  }
  auto handoff = std::make_shared<vm::CompiledHandoff>();
  std::thread publisher([&] { handoff->publish(compiled.code); });
  expectTieringInvisible(*module, h, handoff);
  publisher.join();
}

// Coverage probes change nothing a program does (docs/coverage.md): compiled with coverage,
// every program computes the same variables scan by scan (the static image up to the counters,
// which come last) and faults alike; compiled without it, it holds no probe.
TEST_P(Golden, CoverageChangesNothing) {
  const GoldenCase& c = GetParam();
  Header h = parseHeader(readFile(c.headerFile));
  if (h.expectErrors) GTEST_SKIP() << "does not compile";
  SourceManager plainSources, coveredSources;
  Diagnostics plainDiags, coveredDiags;
  auto plain = compileCase(c, h, plainSources, plainDiags);
  auto covered = compileCase(c, h, coveredSources, coveredDiags, st::coverageOptions(true));
  ASSERT_NE(plain, nullptr) << plainDiags.render(plainSources);
  ASSERT_NE(covered, nullptr) << coveredDiags.render(coveredSources);
  EXPECT_TRUE(plain->coverage.probes.empty());
  EXPECT_TRUE(std::none_of(plain->code.begin(), plain->code.end(), [](const bc::Instr& i) { return i.op == bc::Op::COVER; }));
  setCycleTime(*plain, h);
  setCycleTime(*covered, h);
  VirtualClock plainClock, coveredClock;
  plc::Runtime a(*plain, plainClock, runtimeOptions()), b(*covered, coveredClock, runtimeOptions());
  const bool started = a.coldStart();
  ASSERT_EQ(b.coldStart(), started) << b.faultText();
  applySets(*plain, h, a.machine().memory());
  applySets(*covered, h, b.machine().memory());
  const uint32_t size = plain->staticSize;  // the stack after it starts later with the counters
  if (!covered->coverage.probes.empty()) {
    ASSERT_GE(covered->coverage.counterAddress, size);
  }
  for (int64_t k = 1; started && k <= h.cycles; ++k) {
    const bool ran = a.tick();
    ASSERT_EQ(b.tick(), ran) << "scan " << k << ": " << a.faultText() << " / " << b.faultText();
    const uint8_t* x = a.machine().memory();
    const auto diff = std::mismatch(x, x + size, b.machine().memory());
    ASSERT_EQ(diff.first, x + size) << "memory differs at address " << (diff.first - x) << " after scan " << k;
    if (!ran) break;
  }
  EXPECT_EQ(b.faultText(), a.faultText());
}

// Probes between a comparison and its branch would stop the peephole pass fusing them, probes
// are machine code on the AOT backend: the counters (in the memory image) and everything else
// must match the interpreter after every scan. Statements and charts only (each case is a C
// compile).
TEST_P(Golden, CoverageSameOnAot) {
  const GoldenCase& c = GetParam();
  if (c.name.rfind("statements/", 0) != 0 && c.name.rfind("sfc/", 0) != 0) GTEST_SKIP() << "statements/ and sfc/ only";
  Header h = parseHeader(readFile(c.headerFile));
  if (h.expectErrors) GTEST_SKIP() << "does not compile";
  SourceManager sources;
  Diagnostics diags;
  auto module = compileCase(c, h, sources, diags, st::coverageOptions(true));
  ASSERT_NE(module, nullptr) << diags.render(sources);
  ASSERT_FALSE(module->coverage.probes.empty());
  setCycleTime(*module, h);
  const aot::CompileResult compiled = compileAot(*module);
  ASSERT_TRUE(compiled.code) << compiled.error;
  VirtualClock interpClock, aotClock;
  plc::Runtime interp(*module, interpClock, runtimeOptions()), native(*module, aotClock, runtimeOptions());
  native.machine().useCompiled(compiled.code);
  const bool started = interp.coldStart();
  ASSERT_EQ(native.coldStart(), started);
  applySets(*module, h, interp.machine().memory());
  applySets(*module, h, native.machine().memory());
  const uint32_t size = interp.machine().memorySize();
  for (int64_t k = 1; started && k <= h.cycles; ++k) {
    const bool ran = interp.tick();
    ASSERT_EQ(native.tick(), ran) << "scan " << k;
    const uint8_t* a = interp.machine().memory();
    const auto diff = std::mismatch(a, a + size, native.machine().memory());
    ASSERT_EQ(diff.first, a + size) << "memory differs at address " << (diff.first - a) << " after scan " << k;
    if (!ran) break;
  }
}

std::string caseName(const ::testing::TestParamInfo<GoldenCase>& info) {
  std::string n = info.param.name;
  for (auto& ch : n)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return n;
}

INSTANTIATE_TEST_SUITE_P(St, Golden, ::testing::ValuesIn(discover()), caseName);

}  // namespace
