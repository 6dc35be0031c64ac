#include "lang/st/declare/standard_functions.hpp"

#include <cstdlib>
#include <string>

namespace virtcom::st {

namespace {

#define INLINE Lowering{}
#define OPERATOR(o) Lowering{Lowering::Kind::Operator, BinaryOp::o, bc::Native::SQRT}
#define NATIVE(n) Lowering{Lowering::Kind::Native, BinaryOp::Add, bc::Native::n}
constexpr StandardFunction kFunctions[] = {
#define FUNCTION(NAME, Family, minArgs, maxArgs, Naming, parameters, lowering)                                      \
  {StandardFunctionId::NAME, #NAME, StandardFamily::Family, minArgs, maxArgs, ParameterNaming::Naming, parameters, \
   lowering, {}},
#include "lang/st/declare/standard_functions.def"
};
#undef INLINE
#undef OPERATOR
#undef NATIVE

// <FROM>_TO_<TO> (split at the first "_TO_") or TO_<TO>, both named by elementary types.
std::optional<ConversionTypes> conversionByName(std::string_view name) {
  ConversionTypes c;
  ElemType e;
  if (auto pos = name.find("_TO_"); pos != std::string_view::npos) {
    if (!elemTypeByName(name.substr(0, pos), e)) return std::nullopt;
    c.from = e;
    c.fromName = name.substr(0, pos);
    name.remove_prefix(pos + 4);
  } else if (name.starts_with("TO_")) {
    name.remove_prefix(3);
  } else {
    return std::nullopt;
  }
  if (!elemTypeByName(name, c.to)) return std::nullopt;
  return c;
}

}  // namespace

std::span<const StandardFunction> standardFunctions() { return kFunctions; }

std::optional<StandardFunction> findStandardFunction(std::string_view upperName) {
  for (const StandardFunction& f : kFunctions)
    if (f.name == upperName) return f;
  auto conversion = conversionByName(upperName);
  if (!conversion) return std::nullopt;
  return StandardFunction{StandardFunctionId::Conversion, upperName, StandardFamily::Conversion, 1, 1,
                          ParameterNaming::Numbered, "", Lowering{}, *conversion};
}

bool isStandardFunctionName(std::string_view upperName) { return findStandardFunction(upperName).has_value(); }

bool isLibraryNamespace(std::string_view upperName) {
  return upperName == "STANDARD" || upperName == "TC2_STANDARD" || upperName == "IEC61131_STANDARD";
}

std::string_view withoutLibraryNamespace(std::string_view upperName) {
  size_t dot = upperName.find('.');
  if (dot == std::string_view::npos || dot + 1 == upperName.size() || !isLibraryNamespace(upperName.substr(0, dot)))
    return upperName;
  return upperName.substr(dot + 1);
}

std::string_view listedParameter(std::string_view listed, size_t index) {
  for (; index > 0; --index) {
    size_t space = listed.find(' ');
    if (space == std::string_view::npos) return {};
    listed.remove_prefix(space + 1);
  }
  return listed.substr(0, listed.find(' '));
}

int standardParameterIndex(ParameterNaming naming, std::string_view listed, std::string_view upperName) {
  // INn: the number after IN as atoi reads it (no digits: 0)
  auto number = [&] { return std::atoi(std::string(upperName.substr(2)).c_str()); };
  bool numbered = upperName.size() > 2 && upperName.starts_with("IN");
  switch (naming) {
    case ParameterNaming::Listed:
      for (size_t i = 0; !listedParameter(listed, i).empty(); ++i)
        if (listedParameter(listed, i) == upperName) return static_cast<int>(i);
      return -1;
    case ParameterNaming::Selector:
      if (upperName == "K") return 0;
      return numbered ? 1 + number() : -1;
    case ParameterNaming::Numbered:
      if (upperName == "IN") return 0;
      return numbered ? number() - 1 : -1;
  }
  return -1;
}

}  // namespace virtcom::st
