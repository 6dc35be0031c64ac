#pragma once
// The IEC standard functions (standard_functions.def): which names they have, how their named
// arguments bind, how many arguments they take and which code generator family emits them.
// Used by the declarer (the names are reserved, E119) and by code generation.
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "bytecode/instruction.hpp"
#include "core/iec_value.hpp"
#include "lang/syntax/ast.hpp"

namespace virtcom::st {

enum class StandardFamily : uint8_t {
#define FAMILY(Name, what) Name,
#include "lang/st/declare/standard_functions.def"
  Count_
};

// One enumerator per row of the .def, plus Conversion for every <FROM>_TO_<TO> and TO_<TO>.
enum class StandardFunctionId : uint8_t {
#define FUNCTION(NAME, Family, minArgs, maxArgs, Naming, parameters, lowering) NAME,
#include "lang/st/declare/standard_functions.def"
  Conversion
};

// How named arguments are bound to inputs (see the .def).
enum class ParameterNaming : uint8_t { Listed, Numbered, Selector };

// The most inputs an extensible function takes (and the most a named argument may address).
inline constexpr uint8_t kExtensible = 64;

// How a function is emitted: in place, by an ST operator's rules, or as a CALLN.
struct Lowering {
  enum class Kind : uint8_t { Inline, Operator, Native };
  Kind kind = Kind::Inline;
  BinaryOp op = BinaryOp::Add;           // Kind::Operator
  bc::Native native = bc::Native::SQRT;  // Kind::Native
};

// The elementary types of a conversion <FROM>_TO_<TO> (from is empty for TO_<TO>).
struct ConversionTypes {
  std::optional<ElemType> from;
  std::string_view fromName;  // as written in the function's name, for diagnostics
  ElemType to = ElemType::Int;
};

struct StandardFunction {
  StandardFunctionId id;
  std::string_view name;  // upper case
  StandardFamily family;
  uint8_t minArgs;
  uint8_t maxArgs;
  ParameterNaming naming;
  std::string_view parameters;  // ParameterNaming::Listed: the input names, space-separated
  Lowering lowering;
  ConversionTypes conversion;  // StandardFunctionId::Conversion only
};

// Every row of standard_functions.def, in order (the conversions are not rows).
std::span<const StandardFunction> standardFunctions();

// The standard function called `upperName`, a row or a conversion by the naming rule; nullopt
// for any other name. The result's name (and conversion.fromName) view `upperName`.
std::optional<StandardFunction> findStandardFunction(std::string_view upperName);

// True for the names of IEC standard functions (ADD, SEL, LIMIT, REAL_TO_INT, ...), which
// cannot name a variable or POU (IEC 61131-3; CODESYS rejects them too).
bool isStandardFunctionName(std::string_view upperName);

// CODESYS and TwinCAT may qualify a standard library's names by the library's namespace
// (`Standard.TON`, `Tc2_Standard.LEFT`); the standard FBs, types and functions here belong to
// no namespace. True for those namespaces (upper case, without the dot).
bool isLibraryNamespace(std::string_view upperName);
// `upperName` without such a namespace (`STANDARD.TON` -> `TON`); unchanged otherwise.
std::string_view withoutLibraryNamespace(std::string_view upperName);

// The name of input `index` of a Listed function ("" past the end).
std::string_view listedParameter(std::string_view listed, size_t index);

// The index of the input a named argument `upperName` stands for, or -1 if there is none.
// Numbered and Selector names may point past the inputs the call gives (the caller reports).
int standardParameterIndex(ParameterNaming naming, std::string_view listed, std::string_view upperName);

}  // namespace virtcom::st
