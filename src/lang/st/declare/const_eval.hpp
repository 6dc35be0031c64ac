#pragma once
// Compile-time evaluation of constant expressions: array bounds, string lengths, enum values,
// CASE labels, initial values, and folding of constant operands during code generation.
#include <functional>
#include <optional>

#include "core/diagnostics.hpp"
#include "lang/st/declare/program_model.hpp"

namespace virtcom::st {

struct ConstContext {
  // Resolves a bare or dotted name (a CONSTANT, an enum value `Red`, `Color.Red`) to its value.
  std::function<std::optional<ConstValue>(const Expr&)> lookupName;
  // Resolves `Type#Value` for enums.
  std::function<std::optional<ConstValue>(const std::string& type, const std::string& value)> lookupEnum;
};

// Evaluates `e`; reports E1xx diagnostics and returns nullopt if it is not constant or invalid.
// `quiet` suppresses the "not constant" diagnostic (for opportunistic folding).
std::optional<ConstValue> evalConst(const Expr& e, const ConstContext& ctx, Diagnostics& diags, bool quiet = false);

// Folds a binary operation on two constants; `real` chooses floating point. Returns nullopt for
// division by zero or an operation that does not apply (the caller reports it).
std::optional<ConstValue> foldBinary(BinaryOp op, const ConstValue& a, const ConstValue& b, bool real);
std::optional<ConstValue> foldUnary(UnaryOp op, const ConstValue& a, bool real);

// A string literal of exactly one character as a CHAR (its byte) or WCHAR (its UTF-16 code
// unit) constant, typed; nullopt for any other value. IEC 61131-3 ed. 3 types 'a' and "a" by
// their context: this is where a one-character literal becomes a character.
std::optional<ConstValue> characterConstant(const ConstValue& v, ElemType charType);

// The constant as an integer / real (converting between the two).
int64_t constAsInt(const ConstValue& v);
double constAsReal(const ConstValue& v);

}  // namespace virtcom::st
