#pragma once
// Test-only: report output compared with its golden file in tests/unit/report/golden/.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "support/read_file.hpp"

namespace virtcom::report::testing {

// Compares `actual` with golden/<name>; VIRTCOM_UPDATE_GOLDEN=1 rewrites the file for review in
// the diff.
inline void expectGolden(const std::string& name, const std::string& actual) {
  const std::filesystem::path file = std::filesystem::path(VIRTCOM_SOURCE_DIR) / "tests" / "unit" / "report" / "golden" / name;
  if (std::getenv("VIRTCOM_UPDATE_GOLDEN")) {
    std::ofstream(file, std::ios::binary) << actual;
    return;
  }
  ASSERT_TRUE(std::filesystem::exists(file)) << "missing " << file << "; run with VIRTCOM_UPDATE_GOLDEN=1 and review it";
  EXPECT_EQ(virtcom::test::readFile(file), actual) << "differs from " << file << " (VIRTCOM_UPDATE_GOLDEN=1 rewrites it)";
}

}  // namespace virtcom::report::testing
