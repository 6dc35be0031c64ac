#pragma once
// Bytes as the golden-bytes tests write them: "0D 00 FF", two hex digits a byte, one space apart.
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

namespace virtcom::proto::opcua::testing {

inline std::string hex(const std::vector<uint8_t>& b) {
  std::string out;
  char h[4];
  for (uint8_t c : b) {
    std::snprintf(h, sizeof h, "%02X ", c);
    out += h;
  }
  if (!out.empty()) out.pop_back();
  return out;
}

inline std::vector<uint8_t> unhex(std::string_view text) {
  std::vector<uint8_t> out;
  for (size_t i = 0; i + 1 < text.size() + 1; i += 3) out.push_back(static_cast<uint8_t>(std::stoul(std::string(text.substr(i, 2)), nullptr, 16)));
  return out;
}

}  // namespace virtcom::proto::opcua::testing
