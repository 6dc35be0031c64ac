// The module file (src/bytecode/module_file.*): every program of the golden suite and the gearbox
// cell's program read back equal to what was written (written again, the same bytes: every member
// is in the file, which module_file.cpp's member counts enforce), and broken bytes refused with
// a reason, never a crash.
#include "bytecode/module_file.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/content_hash.hpp"
#include "lang/st/compiler.hpp"

namespace virtcom::bc {
namespace {

namespace fs = std::filesystem;

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream buf;
  buf << in.rdbuf();
  return buf.str();
}

std::unique_ptr<Module> compileFiles(const std::vector<fs::path>& files, bool coverage) {
  std::vector<st::SourceInput> inputs;
  for (const fs::path& f : files) inputs.push_back({f.string(), readFile(f)});
  SourceManager sources;
  Diagnostics diags;
  return st::compileProgram(inputs, sources, diags, st::coverageOptions(coverage));
}

void expectRoundTrip(const Module& m, const std::string& what) {
  const std::string bytes = encodeModule(m);
  Module back;
  EXPECT_EQ(decodeModule(bytes, back), "") << what;
  EXPECT_TRUE(encodeModule(back) == bytes) << what << ": read back differs";
  EXPECT_EQ(back.code.size(), m.code.size()) << what;
  EXPECT_EQ(back.files, m.files) << what;
}

TEST(ModuleFile, EveryGoldenProgramReadsBackEqual) {
  int compiled = 0;
  for (const auto& e : fs::recursive_directory_iterator(fs::path(VIRTCOM_SOURCE_DIR) / "tests/golden/st")) {
    if (e.path().extension() != ".st") continue;
    for (bool coverage : {false, true}) {
      auto m = compileFiles({e.path()}, coverage);
      if (!m) continue;  // the error cases
      ++compiled;
      expectRoundTrip(*m, e.path().string());
    }
  }
  EXPECT_GT(compiled, 200);
}

TEST(ModuleFile, TheGearboxProgramReadsBackEqual) {
  std::vector<fs::path> files;
  for (const char* name : {"types", "GVL", "handshake", "sequences", "jobs", "main"})  // as cell.yaml lists them
    files.push_back(fs::path(VIRTCOM_SOURCE_DIR) / "examples/gearbox-cell/plc" / (std::string(name) + ".st"));
  auto m = compileFiles(files, true);
  ASSERT_TRUE(m);
  expectRoundTrip(*m, "gearbox");
}

const char* kSmall =
    "TYPE Color : (Red, Green); END_TYPE\n"
    "PROGRAM MAIN\nVAR x : DINT; c : Color; s : STRING(8) := 'ab'; a : ARRAY[1..3] OF INT; t : TON; END_VAR\n"
    "x := x + 1; t(IN := x > 2, PT := T#1s); IF t.Q THEN c := Green; END_IF\nEND_PROGRAM\n";

std::string smallModuleBytes() {
  SourceManager sources;
  Diagnostics diags;
  auto m = st::compileProgram({{"main.st", kSmall}}, sources, diags, st::coverageOptions(true));
  return m ? encodeModule(*m) : std::string();
}

// The checksum of `bytes` recomputed after a change, so the change reaches the member readers.
std::string withChecksum(std::string bytes) {
  const size_t body = bytes.size() - sizeof(uint64_t);
  const uint64_t h = hashText(std::string_view(bytes).substr(0, body));
  std::memcpy(bytes.data() + body, &h, sizeof h);
  return bytes;
}

TEST(ModuleFile, EveryTruncationIsRefused) {
  const std::string bytes = smallModuleBytes();
  ASSERT_FALSE(bytes.empty());
  for (size_t n = 0; n < bytes.size(); ++n) {
    Module m;
    EXPECT_NE(decodeModule(std::string_view(bytes).substr(0, n), m), "") << n;
  }
}

TEST(ModuleFile, AChangedByteFailsTheChecksum) {
  std::string bytes = smallModuleBytes();
  bytes[bytes.size() / 2] ^= 0x40;
  Module m;
  EXPECT_EQ(decodeModule(bytes, m), "checksum mismatch");
}

TEST(ModuleFile, ForeignBytesAndOtherVersionsAreRefused) {
  Module m;
  EXPECT_EQ(decodeModule("PK\x03\x04 something else entirely", m), "not a virtcom module file");
  std::string bytes = smallModuleBytes();
  bytes[8] = 99;  // the format version's low byte
  EXPECT_EQ(decodeModule(withChecksum(bytes), m), "format version 99, expected 1");
}

// Any byte at any place, with a valid checksum: read or refused, never a crash (ASan checks the
// reads); a refusal names the part of the file.
TEST(ModuleFile, AnyByteAnywhereIsReadOrRefused) {
  const std::string bytes = smallModuleBytes();
  ASSERT_FALSE(bytes.empty());
  int refused = 0;
  // Every 5th byte (a prime step meets every member kind; every byte takes a minute under ASan).
  for (size_t at = 12; at + sizeof(uint64_t) < bytes.size(); at += 5)
    for (unsigned char value : {0x02, 0xff}) {
      std::string changed = bytes;
      changed[at] = static_cast<char>(value);
      Module m;
      if (!decodeModule(withChecksum(changed), m).empty()) ++refused;
    }
  EXPECT_GT(refused, 0);
}

}  // namespace
}  // namespace virtcom::bc
