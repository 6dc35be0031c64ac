#include "core/bundled_module.hpp"

#include <gtest/gtest.h>

#include <filesystem>

namespace virtcom {
namespace {

TEST(BundledModule, AMissingModuleIsNamedWithWhereItWasLookedFor) {
  auto symbol = bundledModuleSymbol("virtcom-no-such-module.so", "virtcomNothing");
  ASSERT_FALSE(symbol);
  const std::string beside = (std::filesystem::read_symlink("/proc/self/exe").parent_path() / "virtcom-no-such-module.so").string();
  EXPECT_EQ(symbol.error(), "cannot load the module virtcom-no-such-module.so (built and installed beside the virtcom executable): " +
                                beside + ": cannot open shared object file: No such file or directory");
}

}  // namespace
}  // namespace virtcom
