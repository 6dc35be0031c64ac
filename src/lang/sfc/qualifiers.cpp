#include <array>

#include "core/ascii.hpp"
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

}  // namespace

std::string_view qualifierSpelling(Qualifier q) { return kQualifiers[static_cast<size_t>(q)].spelling; }

bool qualifierNeedsTime(Qualifier q) { return kQualifiers[static_cast<size_t>(q)].needsTime; }

std::optional<Qualifier> qualifierFromText(std::string_view text) {
  for (size_t i = 0; i < kQualifiers.size(); ++i) {
    if (iequalsAscii(text, kQualifiers[i].spelling)) return static_cast<Qualifier>(i);
  }
  return std::nullopt;
}

}  // namespace virtcom::sfc
