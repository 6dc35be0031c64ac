#include <array>

#include "lang/sfc/sfc_model.hpp"

namespace virtcom::sfc {

namespace {

struct QualifierInfo {
  std::string_view spelling;
  bool needsTime;
};

constexpr std::array kQualifiers = {
#define X(name, spelling, needsTime, description) QualifierInfo{spelling, needsTime},
#include "lang/sfc/qualifiers.def"
#undef X
};

char upperChar(char c) { return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c; }

}  // namespace

std::string_view qualifierSpelling(Qualifier q) { return kQualifiers[static_cast<size_t>(q)].spelling; }

bool qualifierNeedsTime(Qualifier q) { return kQualifiers[static_cast<size_t>(q)].needsTime; }

std::optional<Qualifier> qualifierFromText(std::string_view text) {
  for (size_t i = 0; i < kQualifiers.size(); ++i) {
    std::string_view s = kQualifiers[i].spelling;
    bool same = s.size() == text.size();
    for (size_t k = 0; same && k < s.size(); ++k) same = upperChar(text[k]) == s[k];
    if (same) return static_cast<Qualifier>(i);
  }
  return std::nullopt;
}

}  // namespace virtcom::sfc
