// The module cache (src/lang/st/compile_cache.*): a second compile of the same inputs reads the
// first one's module back (equal, its files registered as a compile registers them); what the
// key holds (text, path, options, files registered before) decides a hit; a compile with
// diagnostics is not kept; a broken cache file is compiled again and replaced.
#include "lang/st/compile_cache.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "bytecode/module_file.hpp"
#include "core/build_id.hpp"

namespace virtcom::st {
namespace {

namespace fs = std::filesystem;

const char* kProgram = "PROGRAM MAIN\nVAR x : DINT; END_VAR\nx := x + 1;\nEND_PROGRAM\n";
// Compiles with a warning (W302: a FOR loop with BY 0 never ends).
const char* kWarning = "PROGRAM MAIN\nVAR i : INT; END_VAR\nFOR i := 1 TO 3 BY 0 DO\nEND_FOR;\nEND_PROGRAM\n";

class ModuleCache : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_FALSE(binaryBuildId().empty()) << "the test binary has no build id";
    dir_ = fs::temp_directory_path() / ("virtcom-module-cache-test-" + std::to_string(getpid()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  struct Compiled {
    std::unique_ptr<bc::Module> module;
    SourceManager sources;
    Diagnostics diags;
  };
  std::unique_ptr<Compiled> compile(const std::vector<SourceInput>& inputs, bool coverage = false) {
    auto c = std::make_unique<Compiled>();
    CompileOptions options = coverageOptions(coverage);
    options.cacheDir = dir_.string();
    c->module = compileProgram(inputs, c->sources, c->diags, options);
    return c;
  }
  size_t cachedFiles() const {
    size_t n = 0;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir_, ec)) n += e.path().extension() == ".module";
    return n;
  }
  fs::path onlyCachedFile() const { return fs::directory_iterator(dir_)->path(); }

  fs::path dir_;
};

TEST_F(ModuleCache, TheSecondCompileReadsTheFirstBack) {
  auto first = compile({{"main.st", kProgram}});
  ASSERT_TRUE(first->module);
  EXPECT_EQ(cachedFiles(), 1u);
  const auto written = fs::last_write_time(onlyCachedFile());
  auto second = compile({{"main.st", kProgram}});
  ASSERT_TRUE(second->module);
  EXPECT_EQ(bc::encodeModule(*second->module), bc::encodeModule(*first->module));
  EXPECT_EQ(fs::last_write_time(onlyCachedFile()), written) << "a hit rewrote the file";
  // The files are registered as the compile registers them: diagnostics and tools quote them.
  ASSERT_EQ(second->sources.fileCount(), first->sources.fileCount());
  for (uint32_t i = 0; i < first->sources.fileCount(); ++i) {
    EXPECT_EQ(second->sources.path(i), first->sources.path(i));
    EXPECT_EQ(second->sources.text(i), first->sources.text(i));
  }
  EXPECT_TRUE(second->diags.all().empty());
}

TEST_F(ModuleCache, TextPathAndOptionsAreInTheKey) {
  compile({{"main.st", kProgram}});
  compile({{"other.st", kProgram}});
  compile({{"main.st", std::string(kProgram) + "\n"}});
  compile({{"main.st", kProgram}}, true);
  EXPECT_EQ(cachedFiles(), 4u);
  auto covered = compile({{"main.st", kProgram}}, true);
  EXPECT_FALSE(covered->module->coverage.probes.empty());
  auto plain = compile({{"main.st", kProgram}});
  EXPECT_TRUE(plain->module->coverage.probes.empty());
}

TEST_F(ModuleCache, FilesRegisteredBeforeAreInTheKey) {
  const std::vector<SourceInput> inputs{{"main.st", kProgram}};
  const std::string alone = moduleCacheKey(inputs, SourceManager(), {});
  SourceManager withCell;
  withCell.addFile("cell.yaml", "devices: {}\n");
  EXPECT_NE(moduleCacheKey(inputs, withCell, {}), alone);
  EXPECT_EQ(moduleCacheKey(inputs, SourceManager(), {}), alone);
}

TEST_F(ModuleCache, ACompileWithDiagnosticsIsNotKept) {
  auto warned = compile({{"main.st", kWarning}});
  ASSERT_TRUE(warned->module);
  ASSERT_FALSE(warned->diags.all().empty()) << "the program was meant to warn";
  EXPECT_EQ(cachedFiles(), 0u);
  auto again = compile({{"main.st", kWarning}});
  EXPECT_EQ(again->diags.all().size(), warned->diags.all().size()) << "the warning is printed every time";
  auto failed = compile({{"main.st", "PROGRAM MAIN\nx := 1;\nEND_PROGRAM\n"}});
  EXPECT_FALSE(failed->module);
  EXPECT_EQ(cachedFiles(), 0u);
}

TEST_F(ModuleCache, ABrokenFileIsCompiledAgainAndReplaced) {
  auto first = compile({{"main.st", kProgram}});
  const fs::path file = onlyCachedFile();
  std::ofstream(file, std::ios::binary | std::ios::trunc) << "not a module";
  auto second = compile({{"main.st", kProgram}});
  ASSERT_TRUE(second->module);
  EXPECT_EQ(bc::encodeModule(*second->module), bc::encodeModule(*first->module));
  EXPECT_GT(fs::file_size(file), 100u) << "the broken file was not replaced";
}

TEST(ModuleCacheDir, TheEnvironmentChoosesOrTurnsItOff) {
  ::setenv("VIRTCOM_MODULE_CACHE", "/some/where", 1);
  EXPECT_EQ(defaultModuleCacheDir(), "/some/where");
  ::setenv("VIRTCOM_MODULE_CACHE", "off", 1);
  EXPECT_EQ(defaultModuleCacheDir(), "");
  ::unsetenv("VIRTCOM_MODULE_CACHE");
  ::setenv("XDG_CACHE_HOME", "/xdg", 1);
  EXPECT_EQ(defaultModuleCacheDir(), "/xdg/virtcom/modules");
  ::unsetenv("XDG_CACHE_HOME");
}

}  // namespace
}  // namespace virtcom::st
