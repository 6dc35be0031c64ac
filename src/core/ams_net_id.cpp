#include "core/ams_net_id.hpp"

#include <charconv>
#include <optional>

namespace virtcom {

namespace {

std::optional<AmsNetId> netIdFrom(std::string_view text) {
  AmsNetId id{};
  for (size_t i = 0; i < id.size(); ++i) {
    unsigned v = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc{} || end == text.data() || v > 255) return std::nullopt;
    id[i] = static_cast<uint8_t>(v);
    text.remove_prefix(static_cast<size_t>(end - text.data()));
    if (i + 1 < id.size()) {
      if (text.empty() || text.front() != '.') return std::nullopt;
      text.remove_prefix(1);
    }
  }
  if (!text.empty()) return std::nullopt;
  return id;
}

}  // namespace

TextResult<AmsNetId> parseNetId(std::string_view text) {
  if (auto id = netIdFrom(text)) return *id;
  // appended, not "'" + std::string(text): GCC 12 warns falsely about the latter
  std::string message(1, '\'');
  return TextResult<AmsNetId>::failure(message.append(text).append("' is not an AmsNetId (six numbers 0-255, e.g. 192.168.1.10.1.1)"));
}

std::string formatNetId(const AmsNetId& id) {
  std::string s;
  for (size_t i = 0; i < id.size(); ++i) {
    if (i) s += '.';
    s += std::to_string(id[i]);
  }
  return s;
}

}  // namespace virtcom
