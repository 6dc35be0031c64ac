#include "lang/syntax/diagnostic_codes.hpp"

#include "core/code_titles.hpp"

namespace virtcom::st {

namespace {
constexpr CodeTitle kCodeTitles[] = {
#define X(code, title) {#code, title},
#include "lang/syntax/diagnostic_codes.def"
#undef X
};
}  // namespace

std::string_view diagnosticTitle(std::string_view code) { return codeTitle(kCodeTitles, code); }

}  // namespace virtcom::st
