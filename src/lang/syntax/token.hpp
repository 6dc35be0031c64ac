#pragma once
// The tokens of Structured Text as the lexer hands them to the parser.
#include <cstdint>
#include <string>
#include <string_view>

#include "core/source.hpp"

namespace virtcom::st {

enum class Tok : uint16_t {
  Eof,
  Identifier,
  IntLiteral,      // intValue (decimal or based 2#/8#/16#; never negative)
  RealLiteral,     // realValue
  StringLiteral,   // '...': str = decoded bytes
  WStringLiteral,  // "...": str = decoded text as UTF-8
  TypedPrefix,     // `INT#`, `Color#`: text = the prefix without '#'; the value follows as tokens
  TimeLiteral,     // T#/TIME#/LT#/LTIME#: intValue = magnitude in ns, negative, str "TIME"/"LTIME"
  DateLiteral,     // D#/TOD#/DT#: intValue = s since 1970 (DATE, DT) or ms since midnight (TOD);
                   // str = "DATE" / "TOD" / "DT"
  DirectAddress,   // %IX0.0, %QW2, %MD4, %I*, and the bit-access form %X3: text as written
  Pragma,          // {...}: text is the whole pragma including the braces
#define X(name, spelling) name,
#include "lang/syntax/tokens.def"
#undef X
  Count_,
};

struct Token {
  Tok kind = Tok::Eof;
  SourceLocation loc;
  std::string_view text;   // the exact source spelling (points into the lexed text)
  uint64_t intValue = 0;   // IntLiteral, TimeLiteral, DateLiteral
  double realValue = 0;    // RealLiteral
  bool negative = false;   // TimeLiteral written with a '-' sign (T#-5s)
  std::string str;         // decoded string literal; time/date type name
};

// How a token kind is spelled in messages: "END_IF", ":=", or a class name ("identifier").
std::string_view tokSpelling(Tok kind);
// True for the reserved words of tokens.def (IF, END_VAR, GET, ...).
bool isKeyword(Tok kind);

}  // namespace virtcom::st
