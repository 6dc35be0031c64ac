#include "lang/st/parse/lexer.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>

#include "core/ascii.hpp"
#include "core/iec_literal.hpp"
#include "core/iec_value.hpp"
#include "lang/syntax/diagnostic_codes.hpp"

namespace virtcom::st {

namespace {

bool isLetter(char c) { return isAsciiLetter(c) || c == '_'; }
bool isIdentChar(char c) { return isLetter(c) || isAsciiDigit(c); }

int hexDigitValue(char c) {
  const int digit = asciiDigitValue(c);
  return digit < 16 ? digit : -1;
}

void appendUtf8(std::string& out, uint32_t cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

const std::unordered_map<std::string, Tok>& keywordTable() {
  static const std::unordered_map<std::string, Tok> table = [] {
    std::unordered_map<std::string, Tok> t;
    auto add = [&t](Tok kind, std::string_view spelling) {
      // Only word-like spellings are keywords; REF= is recognised separately.
      if (isLetter(spelling[0]) && spelling.find('=') == std::string_view::npos)
        t.emplace(std::string(spelling), kind);
    };
#define X(name, spelling) add(Tok::name, spelling);
#include "lang/syntax/tokens.def"
#undef X
    return t;
  }();
  return table;
}

// ---- The lexer ------------------------------------------------------------------------------

class Lexer {
 public:
  Lexer(uint32_t fileId, std::string_view src, Diagnostics& diags, SourceLocation origin)
      : fileId_(fileId), src_(src), diags_(diags), line_(origin.line), firstLineShift_(origin.col - 1) {}

  std::vector<Token> run() {
    // Room for one token per 3 bytes of source, more than ST holds, so the vector is not
    // copied as it grows: a growing vector touched about twice its final memory, and a page
    // fault on each new page was a third of a gearbox run's page faults. Pages reserved but
    // never written cost nothing (docs/performance.md, "Start-up").
    out_.reserve(src_.size() / 3 + 1);
    while (!atEnd()) lexOne();
    Token eof;
    eof.kind = Tok::Eof;
    eof.loc = here();
    out_.push_back(eof);
    return std::move(out_);
  }

 private:
  bool atEnd() const { return pos_ >= src_.size(); }
  char peek(size_t ahead = 0) const { return pos_ + ahead < src_.size() ? src_[pos_ + ahead] : '\0'; }
  bool startsWith(std::string_view s) const { return src_.substr(pos_, s.size()) == s; }
  void bump() {
    if (src_[pos_] == '\n') {
      ++line_;
      lineStart_ = pos_ + 1;
      firstLineShift_ = 0;
    }
    ++pos_;
  }
  void bump(size_t n) {
    while (n-- > 0 && !atEnd()) bump();
  }
  SourceLocation here() const {
    return {fileId_, line_, static_cast<uint32_t>(pos_ - lineStart_ + 1) + firstLineShift_};
  }
  std::string_view textFrom(size_t start) const { return src_.substr(start, pos_ - start); }

  Token& emit(Tok kind, size_t start, SourceLocation loc) {
    Token t;
    t.kind = kind;
    t.loc = loc;
    t.text = textFrom(start);
    out_.push_back(std::move(t));
    return out_.back();
  }

  void error(std::string_view code, SourceLocation loc, std::string message) {
    diags_.error(code, loc, std::move(message));
  }

  void lexOne() {
    char c = peek();
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v') return bump();
    if (startsWith("(*")) return skipBlockComment("(*", "*)");
    if (startsWith("/*")) return skipBlockComment("/*", "*/");
    if (startsWith("//")) {
      while (!atEnd() && peek() != '\n') bump();
      return;
    }
    if (c == '{') return lexPragma();
    if (isLetter(c)) return lexIdentifier();
    if (isAsciiDigit(c)) return lexNumber();
    if (c == '\'' || c == '"') return lexString(c);
    if (c == '%') return lexDirectAddress();
    lexPunctuation();
  }

  // Comments of one style nest: (* a (* b *) c *) is one comment.
  void skipBlockComment(std::string_view open, std::string_view close) {
    SourceLocation loc = here();
    bump(2);
    size_t depth = 1;
    while (!atEnd()) {
      if (startsWith(open)) {
        bump(2);
        ++depth;
      } else if (startsWith(close)) {
        bump(2);
        if (--depth == 0) return;
      } else {
        bump();
      }
    }
    error(diag::E002, loc, "unterminated comment: '" + std::string(open) + "' has no matching '" + std::string(close) + "'");
  }

  // {attribute 'x'} and other pragmas; the parser decides what they mean.
  void lexPragma() {
    size_t start = pos_;
    SourceLocation loc = here();
    bump();
    char quote = 0;
    while (!atEnd()) {
      char c = peek();
      if (c == '\n' && quote != 0) quote = 0;  // a stray quote must not swallow the file
      if (quote == 0 && c == '}') {
        bump();
        emit(Tok::Pragma, start, loc);
        return;
      }
      if (c == '\'' || c == '"') quote = (quote == 0) ? c : (quote == c ? 0 : quote);
      bump();
    }
    error(diag::E009, loc, "unterminated pragma: '{' has no matching '}'");
  }

  void lexIdentifier() {
    size_t start = pos_;
    SourceLocation loc = here();
    while (isIdentChar(peek())) bump();
    std::string_view word = textFrom(start);
    if (peek() == '#') return lexTypedLiteral(start, loc, word);
    if (iequalsAscii(word, "REF") && peek() == '=' && peek(1) != '>') {
      bump();
      emit(Tok::RefAssignOp, start, loc);
      return;
    }
    auto it = keywordTable().find(asciiUpper(word));
    emit(it == keywordTable().end() ? Tok::Identifier : it->second, start, loc);
  }

  // `word#...`: time and date literals are decoded here because their bodies (1h2m, 2024-01-31)
  // are not ordinary tokens; any other prefix (INT#, Color#) becomes a TypedPrefix token.
  void lexTypedLiteral(size_t start, SourceLocation loc, std::string_view word) {
    bump();  // '#'
    switch (literalFamily(word)) {
      case LiteralFamily::Time: return lexDuration(start, loc, "TIME");
      case LiteralFamily::Ltime: return lexDuration(start, loc, "LTIME");
      case LiteralFamily::Date: return lexDateLike(start, loc, LiteralFamily::Date, "DATE");
      case LiteralFamily::Tod: return lexDateLike(start, loc, LiteralFamily::Tod, "TOD");
      case LiteralFamily::Dt: return lexDateLike(start, loc, LiteralFamily::Dt, "DT");
      case LiteralFamily::Ldate: return lexDateLike(start, loc, LiteralFamily::Ldate, "LDATE");
      case LiteralFamily::Ltod: return lexDateLike(start, loc, LiteralFamily::Ltod, "LTOD");
      case LiteralFamily::Ldt: return lexDateLike(start, loc, LiteralFamily::Ldt, "LDT");
      case LiteralFamily::None: break;
    }
    Token& t = emit(Tok::TypedPrefix, start, loc);
    t.text = word;
  }

  void lexDuration(size_t start, SourceLocation loc, std::string_view typeName) {
    size_t bodyStart = pos_;
    if (peek() == '-' || peek() == '+') bump();
    while (isIdentChar(peek()) || (peek() == '.' && isAsciiDigit(peek(1)))) bump();
    std::string_view body = textFrom(bodyStart);
    Token& t = emit(Tok::TimeLiteral, start, loc);
    t.str = typeName;
    LiteralError why;
    if (!decodeDuration(body, t.intValue, t.negative, why)) malformedLiteral(loc, typeName, t.text, why);
  }

  void lexDateLike(size_t start, SourceLocation loc, LiteralFamily family, std::string_view typeName) {
    size_t bodyStart = pos_;
    while (isIdentChar(peek()) || peek() == ':' || peek() == '-' || (peek() == '.' && isAsciiDigit(peek(1)))) bump();
    std::string body;
    for (char c : textFrom(bodyStart))
      if (c != '_') body += c;
    Token& t = emit(Tok::DateLiteral, start, loc);
    t.str = typeName;
    int64_t value = 0;
    LiteralError why;
    bool ok = decodeLiteralBody(body, family, value, why);
    t.intValue = static_cast<uint64_t>(value);
    if (!ok) malformedLiteral(loc, typeName, t.text, why);
  }

  void malformedLiteral(SourceLocation loc, std::string_view typeName, std::string_view text, const LiteralError& why) {
    std::string message = "malformed " + std::string(typeName) + " literal '" + std::string(text) + "': " + why.what;
    if (!why.quoted.empty()) message += " '" + asciiUpper(why.quoted) + "'";
    error(diag::E005, loc, message);
  }

  // Consumes digits (of any base up to 36 when `alnum`) and underscores; returns them without
  // the underscores.
  std::string takeDigits(bool alnum) {
    std::string digits;
    while (isAsciiDigit(peek()) || peek() == '_' || (alnum && isAsciiLetter(peek()))) {
      if (peek() != '_') digits += peek();
      bump();
    }
    return digits;
  }

  void lexNumber() {
    size_t start = pos_;
    SourceLocation loc = here();
    // After `.` a number is a bit index (w.3, a.1.2), never the start of a real.
    bool bitIndex = !out_.empty() && out_.back().kind == Tok::Dot;
    std::string digits = takeDigits(false);
    if (peek() == '#') return lexBasedInteger(start, loc, digits);
    bool isReal = false;
    if (!bitIndex && peek() == '.' && isAsciiDigit(peek(1))) {
      isReal = true;
      bump();
      digits += '.' + takeDigits(false);
    }
    bool exponent = peek() == 'e' || peek() == 'E';
    char afterE = peek(1);
    if (!bitIndex && exponent && (isAsciiDigit(afterE) || ((afterE == '+' || afterE == '-') && isAsciiDigit(peek(2))))) {
      isReal = true;
      bump();
      digits += 'e';
      if (!isAsciiDigit(peek())) {
        digits += peek();
        bump();
      }
      digits += takeDigits(false);
    }
    if (isIdentChar(peek())) return malformedNumber(start, loc);
    if (isReal) return emitReal(start, loc, digits);
    Token& t = emit(Tok::IntLiteral, start, loc);
    if (!parseDecimal(digits, t.intValue))
      error(diag::E004, loc, "integer literal '" + std::string(t.text) + "' is too large");
  }

  void lexBasedInteger(size_t start, SourceLocation loc, const std::string& baseDigits) {
    bump();  // '#'
    std::string digits = takeDigits(true);
    Token& t = emit(Tok::IntLiteral, start, loc);
    std::string text(t.text);
    unsigned base = 0;
    if (!parseRadix(baseDigits, base))
      return error(diag::E004, loc, "malformed numeric literal '" + text + "': the base must be 2, 8 or 16");
    if (digits.empty()) return error(diag::E004, loc, "malformed numeric literal '" + text + "': no digits after '#'");
    // The first problem from the left is reported: an overflow before a bad digit wins.
    auto notOfBase = [base](char c) { return static_cast<unsigned>(asciiDigitValue(c)) >= base; };
    const size_t bad = static_cast<size_t>(std::find_if(digits.begin(), digits.end(), notOfBase) - digits.begin());
    uint64_t value = 0;
    if (bad > 0 && !parseDigits(std::string_view(digits).substr(0, bad), base, value))
      return error(diag::E004, loc, "integer literal '" + text + "' is too large");
    if (bad < digits.size())
      return error(diag::E004, loc, "malformed numeric literal '" + text + "': '" + digits[bad] + "' is not a base-" +
                                        std::to_string(base) + " digit");
    t.intValue = value;
  }

  void emitReal(size_t start, SourceLocation loc, const std::string& digits) {
    Token& t = emit(Tok::RealLiteral, start, loc);
    auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), t.realValue);
    if (ec != std::errc() || ptr != digits.data() + digits.size() || !std::isfinite(t.realValue)) {
      t.realValue = 0;
      error(diag::E004, loc, "real literal '" + std::string(t.text) + "' is out of range");
    }
  }

  void malformedNumber(size_t start, SourceLocation loc) {
    while (isIdentChar(peek())) bump();
    emit(Tok::IntLiteral, start, loc);
    error(diag::E004, loc, "malformed numeric literal '" + std::string(textFrom(start)) + "'");
  }

  // '...' (STRING) and "..." (WSTRING) with $-escapes. A literal may not span lines.
  void lexString(char quote) {
    size_t start = pos_;
    SourceLocation loc = here();
    bump();
    bool wide = quote == '"';
    std::string value;
    for (;;) {
      if (atEnd() || peek() == '\n') {
        error(diag::E003, loc, std::string("unterminated string literal: missing closing ") + quote);
        break;
      }
      char c = peek();
      if (c == quote) {
        bump();
        break;
      }
      if (c == '$') {
        decodeEscape(value, wide);
        continue;
      }
      value += c;
      bump();
    }
    Token& t = emit(wide ? Tok::WStringLiteral : Tok::StringLiteral, start, loc);
    t.str = std::move(value);
  }

  // $$ $' $" $L $N $P $R $T (any case); $hh in STRING, $hhhh (to UTF-8) in WSTRING.
  void decodeEscape(std::string& out, bool wide) {
    SourceLocation loc = here();
    bump();  // '$'
    char c = peek();
    switch (asciiUpper(c)) {
      case '$': case '\'': case '"': out += c; return bump();
      case 'L': case 'N': out += '\n'; return bump();
      case 'P': out += '\f'; return bump();
      case 'R': out += '\r'; return bump();
      case 'T': out += '\t'; return bump();
      default: break;
    }
    size_t hexCount = wide ? 4 : 2;
    uint32_t value = 0;
    for (size_t i = 0; i < hexCount; ++i) {
      int d = hexDigitValue(peek(i));
      if (d < 0) {
        std::string shown = (atEnd() || c == '\n') ? "" : std::string(1, c);
        return error(diag::E008, loc, "invalid escape '$" + shown + "' in string literal (expected $$, $', $L, $N, $P, $R, $T or " +
                                          (wide ? "$hhhh" : "$hh") + ")");
      }
      value = value * 16 + static_cast<uint32_t>(d);
    }
    bump(hexCount);
    if (wide)
      appendUtf8(out, value);
    else
      out += static_cast<char>(value);
  }

  // %IX0.0, %QW2, %MD4, %I* (CODESYS placeholder) and %X3 (bit access after a dot).
  void lexDirectAddress() {
    size_t start = pos_;
    SourceLocation loc = here();
    bump();
    size_t lettersStart = pos_;
    while (isAsciiLetter(peek())) bump();
    std::string letters = asciiUpper(textFrom(lettersStart));
    bool star = peek() == '*';
    size_t digitsStart = pos_;
    if (star) {
      bump();
    } else {
      while (isAsciiDigit(peek()) || (peek() == '.' && isAsciiDigit(peek(1)))) bump();
    }
    bool hasDigits = pos_ > digitsStart && !star;
    Token& t = emit(Tok::DirectAddress, start, loc);
    bool areaOk = !letters.empty() && std::string_view("IQM").find(letters[0]) != std::string_view::npos &&
                  (letters.size() == 1 || (letters.size() == 2 && std::string_view("XBWDL").find(letters[1]) != std::string_view::npos));
    // `.%X3`, `.%B1`, `.%W0`, `.%D1`, `.%L0`: partial access to a bit string after a '.'.
    bool bitForm = letters.size() == 1 && std::string_view("XBWDL").find(letters[0]) != std::string_view::npos &&
                   hasDigits && textFrom(digitsStart).find('.') == std::string_view::npos;
    if (!((areaOk && (hasDigits || star)) || bitForm))
      error(diag::E012, loc, "invalid direct address '" + std::string(t.text) +
                                 "' (expected %I, %Q or %M, an optional size X, B, W, D or L, then numbers such as %IX0.1)");
  }

  void lexPunctuation() {
    size_t start = pos_;
    SourceLocation loc = here();
    char c = peek();
    char next = peek(1);
    Tok kind = Tok::Eof;
    size_t length = 1;
    switch (c) {
      case '(': kind = Tok::LParen; break;
      case ')': kind = Tok::RParen; break;
      case '[': kind = Tok::LBracket; break;
      case ']': kind = Tok::RBracket; break;
      case ',': kind = Tok::Comma; break;
      case ';': kind = Tok::Semicolon; break;
      case ':': kind = next == '=' ? Tok::Assign : Tok::Colon; break;
      case '=': kind = next == '>' ? Tok::OutAssign : Tok::Eq; break;
      case '.': kind = next == '.' ? Tok::DotDot : Tok::Dot; break;
      case '^': kind = Tok::Caret; break;
      case '#': kind = Tok::Hash; break;
      case '+': kind = Tok::Plus; break;
      case '-': kind = Tok::Minus; break;
      case '*': kind = next == '*' ? Tok::Power : Tok::Star; break;
      case '/': kind = Tok::Slash; break;
      case '&': kind = Tok::Amp; break;
      case '<': kind = next == '=' ? Tok::Le : next == '>' ? Tok::Ne : Tok::Lt; break;
      case '>': kind = next == '=' ? Tok::Ge : Tok::Gt; break;
      case '?':
        if (next != '=') return invalidCharacter(loc);
        kind = Tok::AttemptAssignOp;
        break;
      default: return invalidCharacter(loc);
    }
    bool twoChars = (kind == Tok::Assign || kind == Tok::OutAssign || kind == Tok::DotDot || kind == Tok::Power ||
                     kind == Tok::Le || kind == Tok::Ne || kind == Tok::Ge || kind == Tok::AttemptAssignOp);
    if (twoChars) length = 2;
    bump(length);
    emit(kind, start, loc);
  }

  void invalidCharacter(SourceLocation loc) {
    unsigned char c = static_cast<unsigned char>(peek());
    std::string shown;
    if (c >= 0x20 && c < 0x7F) {
      shown = "'" + std::string(1, static_cast<char>(c)) + "'";
    } else {
      static constexpr char kHex[] = "0123456789ABCDEF";
      shown = std::string("byte 0x") + kHex[c >> 4] + kHex[c & 0xF];
    }
    bump();
    // One diagnostic per UTF-8 character, not per byte.
    if (c >= 0xC0)
      while (!atEnd() && (static_cast<unsigned char>(peek()) & 0xC0) == 0x80) bump();
    error(diag::E001, loc, "invalid character " + shown);
  }

  uint32_t fileId_;
  std::string_view src_;
  Diagnostics& diags_;
  size_t pos_ = 0;
  uint32_t line_ = 1;
  size_t lineStart_ = 0;
  uint32_t firstLineShift_ = 0;  // a fragment's first line starts at column origin.col
  std::vector<Token> out_;
};

}  // namespace

std::string_view tokSpelling(Tok kind) {
  switch (kind) {
    case Tok::Eof: return "end of file";
    case Tok::Identifier: return "identifier";
    case Tok::IntLiteral: return "integer literal";
    case Tok::RealLiteral: return "real literal";
    case Tok::StringLiteral: return "string literal";
    case Tok::WStringLiteral: return "wide string literal";
    case Tok::TypedPrefix: return "typed literal";
    case Tok::TimeLiteral: return "time literal";
    case Tok::DateLiteral: return "date literal";
    case Tok::DirectAddress: return "direct address";
    case Tok::Pragma: return "pragma";
#define X(name, spelling) \
  case Tok::name: return spelling;
#include "lang/syntax/tokens.def"
#undef X
    case Tok::Count_: break;
  }
  return "?";
}

bool isKeyword(Tok kind) {
  std::string_view s = tokSpelling(kind);
  return kind > Tok::Pragma && kind < Tok::Count_ && isLetter(s[0]) && s.find('=') == std::string_view::npos;
}

std::vector<Token> lex(uint32_t fileId, std::string_view text, Diagnostics& diags) {
  return Lexer(fileId, text, diags, {fileId, 1, 1}).run();
}

std::vector<Token> lexFragment(uint32_t fileId, SourceLocation origin, std::string_view text, Diagnostics& diags) {
  return Lexer(fileId, text, diags, origin).run();
}

std::u16string utf8ToUtf16(std::string_view utf8) {
  std::u16string out;
  size_t i = 0;
  while (i < utf8.size()) {
    const auto lead = static_cast<unsigned char>(utf8[i]);
    size_t extra = lead >= 0xF0 ? 3 : lead >= 0xE0 ? 2 : lead >= 0xC0 ? 1 : 0;
    uint32_t cp = extra == 3 ? lead & 0x07u : extra == 2 ? lead & 0x0Fu : extra == 1 ? lead & 0x1Fu : lead;
    bool wellFormed = i + extra < utf8.size() || extra == 0;
    for (size_t k = 1; wellFormed && k <= extra; ++k) {
      const auto cont = static_cast<unsigned char>(utf8[i + k]);
      wellFormed = (cont & 0xC0) == 0x80;
      cp = (cp << 6) | (cont & 0x3Fu);
    }
    if (!wellFormed) {
      cp = lead;
      extra = 0;
    }
    i += extra + 1;
    if (cp > 0xFFFF) {
      cp -= 0x10000;
      out += static_cast<char16_t>(0xD800 + (cp >> 10));
      out += static_cast<char16_t>(0xDC00 + (cp & 0x3FF));
    } else {
      out += static_cast<char16_t>(cp);
    }
  }
  return out;
}

}  // namespace virtcom::st
