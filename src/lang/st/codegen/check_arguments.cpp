// Checks of the arguments of standard function calls: bound to their inputs and counted.
#include "lang/st/codegen/check.hpp"
#include "lang/syntax/diagnostic_codes.hpp"

namespace virtcom::st {

std::optional<std::vector<const Expr*>> orderStandardArguments(Diagnostics& diags, const std::string& name,
                                                               ParameterNaming naming, std::string_view listed,
                                                               const Expr& call) {
  std::vector<const Expr*> ordered;
  for (const auto& a : call.args) {
    if (a.output) {
      diags.error(diag::E203, a.loc, name + " has no outputs");
      return std::nullopt;
    }
    size_t index = ordered.size();  // a positional argument follows the previous one
    if (!a.name.empty()) {
      int i = standardParameterIndex(naming, listed, upper(a.name));
      if (i < 0 || i >= kExtensible) {
        diags.error(diag::E203, a.loc, name + " has no input '" + a.name + "'");
        return std::nullopt;
      }
      index = static_cast<size_t>(i);
    }
    if (ordered.size() <= index) ordered.resize(index + 1, nullptr);
    if (ordered[index]) {
      diags.error(diag::E203, a.loc, "input " + std::to_string(index + 1) + " of " + name + " is given twice");
      return std::nullopt;
    }
    ordered[index] = a.value.get();
  }
  for (size_t i = 0; i < ordered.size(); ++i)
    if (!ordered[i]) {
      diags.error(diag::E203, call.loc, name + " is missing input " + std::to_string(i + 1));
      return std::nullopt;
    }
  return ordered;
}

bool checkArgumentCount(Diagnostics& diags, const StandardFunction& fn, SourceLocation loc, size_t count) {
  if (count >= fn.minArgs && count <= fn.maxArgs) return true;
  std::string range = std::to_string(fn.minArgs);
  if (fn.minArgs != fn.maxArgs) range += ".." + std::to_string(fn.maxArgs);
  diags.error(diag::E203, loc, std::string(fn.name) + " takes " + range + " argument(s), found " + std::to_string(count));
  return false;
}

}  // namespace virtcom::st
