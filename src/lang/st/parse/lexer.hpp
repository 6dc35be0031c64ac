#pragma once
// The Structured Text lexer: source text to tokens.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostics.hpp"
#include "lang/syntax/token.hpp"

namespace virtcom::st {

// Splits `text` into tokens, skipping whitespace and comments ((* *) and /* */ nest; //).
// Keywords are recognised case-insensitively; literals are decoded into the token payloads.
// Never throws: lexical errors (E001-E005, E008, E009, E012) go to `diags` and lexing goes on,
// so the result always ends with exactly one Tok::Eof token. Token texts point into `text`,
// which must outlive the tokens.
std::vector<Token> lex(uint32_t fileId, std::string_view text, Diagnostics& diags);

// As lex(), for a fragment of a larger file (e.g. ST text embedded in a PLCopen XML file) whose
// first character sits at `origin` (1-based line and column) of file `fileId`: token and
// diagnostic locations point into that file.
std::vector<Token> lexFragment(uint32_t fileId, SourceLocation origin, std::string_view text, Diagnostics& diags);

// A wide string literal's payload is UTF-8 (so diagnostics can quote it); WSTRING memory holds
// UTF-16 code units. Characters beyond U+FFFF become surrogate pairs; a malformed byte is
// taken as the code unit of its value.
std::u16string utf8ToUtf16(std::string_view utf8);

}  // namespace virtcom::st
