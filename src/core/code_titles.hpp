#pragma once
// A table of diagnostic codes and their short titles, as every code family builds it from its
// X(CODE, "title") `.def` file (ST E/W codes, cell C codes, activity-diagram A codes).
#include <span>
#include <string_view>

namespace virtcom {

struct CodeTitle {
  std::string_view code;
  std::string_view title;
};

// The title of `code` in `table`, or empty if the table has no such code.
constexpr std::string_view codeTitle(std::span<const CodeTitle> table, std::string_view code) {
  for (const CodeTitle& entry : table)
    if (entry.code == code) return entry.title;
  return {};
}

}  // namespace virtcom
