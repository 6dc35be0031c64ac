#include "lang/st/declare/standard_names.hpp"

#include <string>

#include "core/iec_value.hpp"

namespace virtcom::st {

static constexpr std::string_view kNames[] = {
    "ABS",   "SQRT",  "LN",     "LOG",     "EXP",     "SIN",    "COS",    "TAN",    "ASIN",  "ACOS",
    "ATAN",  "ATAN2", "EXPT",   "ADD",     "SUB",     "MUL",    "DIV",    "MOD",    "MOVE",  "SEL",
    "MUX",   "MIN",   "MAX",    "LIMIT",   "SHL",     "SHR",    "ROL",    "ROR",    "GT",    "GE",
    "EQ",    "LE",    "LT",     "NE",      "LEN",     "LEFT",   "RIGHT",  "MID",    "CONCAT", "INSERT",
    "DELETE", "REPLACE", "FIND", "TRUNC",  "SCALE_X", "NORM_X", "ADR",    "REF",    "SIZEOF",
    "AND",   "OR",    "XOR",    "NOT",     "TRUNC_INT"};

bool isStandardFunctionName(std::string_view name) {
  for (auto n : kNames)
    if (n == name) return true;
  // conversions: X_TO_Y and TO_Y
  auto pos = name.find("_TO_");
  ElemType e;
  if (pos != std::string_view::npos)
    return elemTypeByName(name.substr(0, pos), e) && elemTypeByName(name.substr(pos + 4), e);
  if (name.substr(0, 3) == "TO_") return elemTypeByName(name.substr(3), e);
  return false;
}

}  // namespace virtcom::st
