#pragma once
// Test-only: a whole file as bytes (empty if it cannot be read).
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace virtcom::test {

inline std::string readFile(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace virtcom::test
