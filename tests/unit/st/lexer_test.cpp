#include "lang/st/parse/lexer.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "core/iec_value.hpp"
#include "lang/syntax/diagnostic_codes.hpp"

namespace virtcom::st {
namespace {

struct Lexed {
  Diagnostics diags;
  std::vector<Token> tokens;
};

Lexed lexText(std::string_view text) {
  Lexed out;
  out.tokens = lex(0, text, out.diags);
  return out;
}

// Kinds of all tokens but the final Eof, spelled as in messages.
std::string kinds(std::string_view text) {
  Lexed l = lexText(text);
  std::string out;
  for (size_t i = 0; i + 1 < l.tokens.size(); ++i) {
    if (!out.empty()) out += ' ';
    out += tokSpelling(l.tokens[i].kind);
  }
  return out;
}

// The single token of `text` (asserting there is exactly one and no diagnostic).
Token single(std::string_view text) {
  Lexed l = lexText(text);
  EXPECT_EQ(l.tokens.size(), 2u) << text;
  EXPECT_EQ(l.diags.all().size(), 0u) << text << ": " << (l.diags.all().empty() ? "" : l.diags.all()[0].message);
  return l.tokens.empty() ? Token{} : l.tokens[0];
}

std::string firstDiag(std::string_view text) {
  Lexed l = lexText(text);
  if (l.diags.all().empty()) return "(none)";
  const Diagnostic& d = l.diags.all()[0];
  return std::to_string(d.loc.line) + ":" + std::to_string(d.loc.col) + " " + std::string(d.code) + " " + d.message;
}

TEST(Lexer, EmptyInputIsJustEof) {
  Lexed l = lexText("");
  ASSERT_EQ(l.tokens.size(), 1u);
  EXPECT_EQ(l.tokens[0].kind, Tok::Eof);
  EXPECT_EQ(l.tokens[0].loc.line, 1u);
  EXPECT_EQ(l.tokens[0].loc.col, 1u);
}

TEST(Lexer, KeywordsAreCaseInsensitiveIdentifiersKeepTheirCase) {
  EXPECT_EQ(kinds("if If IF end_if Motor_1 _x"), "IF IF IF END_IF identifier identifier");
  Lexed l = lexText("Motor_1");
  EXPECT_EQ(l.tokens[0].text, "Motor_1");
}

TEST(Lexer, Punctuation) {
  EXPECT_EQ(kinds(":= : => = <> <= < >= > .. . ^ ** * + - / & ( ) [ ] , ; #"),
            ":= : => = <> <= < >= > .. . ^ ** * + - / & ( ) [ ] , ; #");
  EXPECT_EQ(kinds("a:=b;"), "identifier := identifier ;");
  EXPECT_EQ(kinds("1..10"), "integer literal .. integer literal");
}

TEST(Lexer, RefAssignOperator) {
  EXPECT_EQ(kinds("r REF= x"), "identifier REF= identifier");
  EXPECT_EQ(kinds("ref = x"), "identifier = identifier");
}

TEST(Lexer, AssignmentAttemptOperator) {
  EXPECT_EQ(kinds("r ?= itf;"), "identifier ?= identifier ;");
  EXPECT_EQ(kinds("r?=itf"), "identifier ?= identifier");
}

TEST(Lexer, LoneQuestionMarkIsAnInvalidCharacter) {
  EXPECT_EQ(firstDiag("a ? b"), "1:3 E001 invalid character '?'");
}

TEST(Lexer, CommentsNestAndAreSkipped) {
  EXPECT_EQ(kinds("a (* one (* nested *) still *) b"), "identifier identifier");
  EXPECT_EQ(kinds("a /* x /* y */ z */ b // to end\nc"), "identifier identifier identifier");
  EXPECT_EQ(kinds("a (* /* *) b"), "identifier identifier");  // styles nest separately
}

TEST(Lexer, UnterminatedCommentIsReportedAtItsStart) {
  EXPECT_EQ(firstDiag("x\n  (* open (* inner *)"), "2:3 E002 unterminated comment: '(*' has no matching '*)'");
  EXPECT_EQ(firstDiag("/* open"), "1:1 E002 unterminated comment: '/*' has no matching '*/'");
}

TEST(Lexer, LocationsAreOneBasedByteColumns) {
  Lexed l = lexText("a\n  bb := 1;\n\tc");
  ASSERT_GE(l.tokens.size(), 6u);
  EXPECT_EQ(l.tokens[1].loc.line, 2u);
  EXPECT_EQ(l.tokens[1].loc.col, 3u);
  EXPECT_EQ(l.tokens[2].loc.col, 6u);
  EXPECT_EQ(l.tokens[5].loc.line, 3u);
  EXPECT_EQ(l.tokens[5].loc.col, 2u);
}

TEST(Lexer, IntegerLiterals) {
  EXPECT_EQ(single("42").intValue, 42u);
  EXPECT_EQ(single("1_000_000").intValue, 1000000u);
  EXPECT_EQ(single("2#1010_1010").intValue, 0xAAu);
  EXPECT_EQ(single("8#17").intValue, 15u);
  EXPECT_EQ(single("16#FF").intValue, 255u);
  EXPECT_EQ(single("16#ff").intValue, 255u);
  EXPECT_EQ(single("18446744073709551615").intValue, 18446744073709551615u);
}

TEST(Lexer, MalformedIntegers) {
  EXPECT_EQ(firstDiag("18446744073709551616"), "1:1 E004 integer literal '18446744073709551616' is too large");
  EXPECT_EQ(firstDiag("2#102"), "1:1 E004 malformed numeric literal '2#102': '2' is not a base-2 digit");
  EXPECT_EQ(firstDiag("7#1"), "1:1 E004 malformed numeric literal '7#1': the base must be 2, 8 or 16");
  EXPECT_EQ(firstDiag("16#"), "1:1 E004 malformed numeric literal '16#': no digits after '#'");
  EXPECT_EQ(firstDiag("12abc"), "1:1 E004 malformed numeric literal '12abc'");
}

TEST(Lexer, RealLiterals) {
  Token t = single("1.5");
  EXPECT_EQ(t.kind, Tok::RealLiteral);
  EXPECT_DOUBLE_EQ(t.realValue, 1.5);
  EXPECT_DOUBLE_EQ(single("1.0E-3").realValue, 1.0e-3);
  EXPECT_EQ(single("1e6").kind, Tok::RealLiteral);
  EXPECT_DOUBLE_EQ(single("1e6").realValue, 1e6);
  EXPECT_DOUBLE_EQ(single("1_000.25").realValue, 1000.25);
  EXPECT_EQ(firstDiag("1e999"), "1:1 E004 real literal '1e999' is out of range");
}

TEST(Lexer, NumberAfterDotIsABitIndex) {
  EXPECT_EQ(kinds("w.3"), "identifier . integer literal");
  EXPECT_EQ(kinds("a.1.2"), "identifier . integer literal . integer literal");
}

TEST(Lexer, StringLiteralsDecodeEscapes) {
  EXPECT_EQ(single("'it$'s'").str, "it's");
  EXPECT_EQ(single("'$$ $L$N$P$R$T $l$n$p$r$t'").str, "$ \n\n\f\r\t \n\n\f\r\t");
  EXPECT_EQ(single("'$41$0a'").str, "A\n");
  EXPECT_EQ(single("'say \"hi\"'").str, "say \"hi\"");
  Token w = single("\"wide $\" $0041 $00e9\"");
  EXPECT_EQ(w.kind, Tok::WStringLiteral);
  EXPECT_EQ(w.str, "wide \" A \xC3\xA9");
  EXPECT_EQ(single("''").str, "");
}

TEST(Lexer, StringErrors) {
  EXPECT_EQ(firstDiag("x := 'open\n;"), "1:6 E003 unterminated string literal: missing closing '");
  EXPECT_EQ(firstDiag("'bad $q'"),
            "1:6 E008 invalid escape '$q' in string literal (expected $$, $', $L, $N, $P, $R, $T or $hh)");
  EXPECT_EQ(firstDiag("\"$12\""),
            "1:2 E008 invalid escape '$1' in string literal (expected $$, $', $L, $N, $P, $R, $T or $hhhh)");
}

constexpr uint64_t kMs = 1'000'000;
constexpr uint64_t kS = 1'000 * kMs;

TEST(Lexer, TimeLiterals) {
  EXPECT_EQ(single("T#1h2m3s4ms").intValue, 3723 * kS + 4 * kMs);
  EXPECT_EQ(single("TIME#5s").intValue, 5 * kS);
  EXPECT_EQ(single("t#1.5s").intValue, 1500 * kMs);
  EXPECT_EQ(single("T#1d").intValue, 86400 * kS);
  EXPECT_EQ(single("T#10us").intValue, 10'000u);
  EXPECT_EQ(single("T#100ns").intValue, 100u);
  EXPECT_EQ(single("T#1_000ms").intValue, kS);
  EXPECT_EQ(single("T#1m_30s").intValue, 90 * kS);
  Token neg = single("T#-5s");
  EXPECT_TRUE(neg.negative);
  EXPECT_EQ(neg.intValue, 5 * kS);
  EXPECT_EQ(neg.str, "TIME");
  Token lt = single("LTIME#1ms5us");
  EXPECT_EQ(lt.str, "LTIME");
  EXPECT_EQ(lt.intValue, kMs + 5000);
  EXPECT_EQ(single("lt#2S").intValue, 2 * kS);
}

TEST(Lexer, TimeLiteralErrors) {
  EXPECT_EQ(firstDiag("T#5"), "1:1 E005 malformed TIME literal 'T#5': missing unit (d, h, m, s, ms, us, ns)");
  EXPECT_EQ(firstDiag("T#5x"), "1:1 E005 malformed TIME literal 'T#5x': unknown unit 'X'");
  EXPECT_EQ(firstDiag("T#"), "1:1 E005 malformed TIME literal 'T#': no value");
  EXPECT_EQ(firstDiag("T#99999999999d"), "1:1 E005 malformed TIME literal 'T#99999999999d': value too large");
}

TEST(Lexer, TimeLiteralsStopBeforeRanges) {
  EXPECT_EQ(kinds("T#1s..T#2s"), "time literal .. time literal");
}

TEST(Lexer, DateLiterals) {
  int64_t jan31 = daysFromCivil(2024, 1, 31) * 86400;
  Token d = single("D#2024-01-31");
  EXPECT_EQ(d.kind, Tok::DateLiteral);
  EXPECT_EQ(d.str, "DATE");
  EXPECT_EQ(static_cast<int64_t>(d.intValue), jan31);
  EXPECT_EQ(static_cast<int64_t>(single("DATE#2024-01-31").intValue), jan31);
  Token tod = single("TOD#12:30:15.5");
  EXPECT_EQ(tod.str, "TOD");
  EXPECT_EQ(tod.intValue, 45015500u);
  EXPECT_EQ(single("TIME_OF_DAY#00:00:01").intValue, 1000u);
  Token dt = single("DT#2024-01-31-12:30:15");
  EXPECT_EQ(dt.str, "DT");
  EXPECT_EQ(static_cast<int64_t>(dt.intValue), jan31 + 45015);
  EXPECT_EQ(static_cast<int64_t>(single("DATE_AND_TIME#1970-01-01-00:00:00").intValue), 0);
}

TEST(Lexer, DateLiteralErrors) {
  EXPECT_EQ(firstDiag("D#2024-02-30"), "1:1 E005 malformed DATE literal 'D#2024-02-30': no such date");
  EXPECT_EQ(firstDiag("D#2023-02-29"), "1:1 E005 malformed DATE literal 'D#2023-02-29': no such date");
  EXPECT_EQ(firstDiag("TOD#25:00:00"), "1:1 E005 malformed TOD literal 'TOD#25:00:00': no such time of day");
  EXPECT_EQ(firstDiag("DT#2024-01-01"), "1:1 E005 malformed DT literal 'DT#2024-01-01': expected yyyy-mm-dd-hh:mm:ss");
}

TEST(Lexer, TypedPrefixes) {
  EXPECT_EQ(kinds("INT#5"), "typed literal integer literal");
  EXPECT_EQ(kinds("INT#-5"), "typed literal - integer literal");
  EXPECT_EQ(kinds("DINT#16#FF"), "typed literal integer literal");
  EXPECT_EQ(kinds("Color#Red"), "typed literal identifier");
  Lexed l = lexText("Color#Red");
  EXPECT_EQ(l.tokens[0].text, "Color");
}

TEST(Lexer, DirectAddresses) {
  for (std::string_view a : {"%IX0.0", "%QW2", "%MD4", "%I0", "%QB10", "%ML1", "%I*", "%X3", "%ix1.7"}) {
    Token t = single(a);
    EXPECT_EQ(t.kind, Tok::DirectAddress) << a;
    EXPECT_EQ(t.text, a);
  }
  EXPECT_EQ(firstDiag("%ZX1"),
            "1:1 E012 invalid direct address '%ZX1' (expected %I, %Q or %M, an optional size X, B, W, D or L, then "
            "numbers such as %IX0.1)");
  EXPECT_NE(firstDiag("%IX"), "(none)");
  EXPECT_NE(firstDiag("%X1.2"), "(none)");
}

TEST(Lexer, PragmasAreTokens) {
  Lexed l = lexText("{attribute 'hide'} x");
  ASSERT_EQ(l.tokens.size(), 3u);
  EXPECT_EQ(l.tokens[0].kind, Tok::Pragma);
  EXPECT_EQ(l.tokens[0].text, "{attribute 'hide'}");
  EXPECT_EQ(kinds("{attribute 'a' := '}'} x"), "pragma identifier");
  EXPECT_EQ(firstDiag("{attribute 'x'"), "1:1 E009 unterminated pragma: '{' has no matching '}'");
}

TEST(Lexer, InvalidCharactersAreReportedOncePerCharacter) {
  Lexed l = lexText("a ? b \xC3\xA9 c");
  ASSERT_EQ(l.diags.all().size(), 2u);
  EXPECT_EQ(l.diags.all()[0].message, "invalid character '?'");
  EXPECT_EQ(l.diags.all()[0].loc.col, 3u);
  EXPECT_EQ(l.diags.all()[1].message, "invalid character byte 0xC3");
  EXPECT_EQ(kinds("a ? b \xC3\xA9 c"), "identifier identifier identifier");
}

TEST(Lexer, RandomBytesNeverCrashAndEndWithEof) {
  std::mt19937 rng(1234);
  std::string alphabet = "abcT#D%IX$'\"(*)/{}[]:=.0123456789_-+ \n\t\x01\xFF";
  for (int round = 0; round < 2000; ++round) {
    std::string text;
    size_t len = rng() % 64;
    for (size_t i = 0; i < len; ++i) text += alphabet[rng() % alphabet.size()];
    Lexed l = lexText(text);
    ASSERT_FALSE(l.tokens.empty());
    EXPECT_EQ(l.tokens.back().kind, Tok::Eof);
  }
}

TEST(DiagnosticCodes, TitlesComeFromTheTable) {
  EXPECT_EQ(diagnosticTitle("E006"), "unexpected token");
  EXPECT_EQ(diagnosticTitle(diag::E010), "nesting too deep");
  EXPECT_EQ(diagnosticTitle("Z000"), "");
}

// A wide literal's payload is UTF-8; WSTRING memory needs UTF-16 code units (bug B7).
TEST(Utf8ToUtf16, OneUnitPerCharacterOfTheBasicPlane) {
  EXPECT_EQ(utf8ToUtf16("a\xC3\xA4\xE2\x82\xAC"), (std::u16string{u'a', u'\u00E4', u'\u20AC'}));
  Lexed l = lexText("\"$00E4$20AC\"");
  EXPECT_EQ(utf8ToUtf16(l.tokens[0].str), (std::u16string{u'\u00E4', u'\u20AC'}));
}

TEST(Utf8ToUtf16, CharactersBeyondTheBasicPlaneBecomeSurrogatePairs) {
  EXPECT_EQ(utf8ToUtf16("\xF0\x9F\x98\x80"), (std::u16string{char16_t(0xD83D), char16_t(0xDE00)}));
}

TEST(Utf8ToUtf16, MalformedBytesAreTakenAsTheirValue) {
  EXPECT_EQ(utf8ToUtf16("\xC3x"), (std::u16string{char16_t(0xC3), u'x'}));
  EXPECT_EQ(utf8ToUtf16("\xE2\x82"), (std::u16string{char16_t(0xE2), char16_t(0x82)}));
}

}  // namespace
}  // namespace virtcom::st
