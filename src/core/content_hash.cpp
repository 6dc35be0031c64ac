#include "core/content_hash.hpp"

#include <cstdio>

namespace virtcom {

uint64_t hashText(std::string_view text, uint64_t seed) {
  uint64_t h = seed;
  for (unsigned char ch : text) h = (h ^ ch) * 0x100000001b3ull;
  return h;
}

std::string hashHex(std::string_view text) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(hashText(text)));
  return buf;
}

}  // namespace virtcom
