#pragma once
// The one reader of IEC literal text: the bodies of time and date literals (what follows T#,
// LTIME#, D#, TOD#, DT#), their prefixes, and integer digits in bases 2, 8, 10 and 16, decoded
// without allocating. The ST lexer decodes literals with it, the VM's STRING_TO_* conversions
// decode run-time text with it, and bytecode's value parser (--set, cell wiring) reads typed
// values with it, so all three accept the same spellings.
#include <cstdint>
#include <string_view>

namespace virtcom {

// Why a body was refused: the kind (for callers with their own wording), a fixed text, and
// the part of the input it is about (the unit of `T#5x`), empty when there is none.
struct LiteralError {
  enum class Kind : uint8_t {
    Malformed,  // not the literal's syntax, or no such date or time of day
    Empty,      // nothing after the prefix and sign
    TooLarge,   // well formed, but beyond the range the decoder can hold
  };
  Kind kind = Kind::Malformed;
  const char* what = "";
  std::string_view quoted;
};

enum class LiteralFamily { None, Time, Ltime, Date, Tod, Dt, Ldate, Ltod, Ldt };

// The family of a literal prefix: T, TIME, LT, LTIME, D, DATE, TOD, TIME_OF_DAY, DT,
// DATE_AND_TIME, LDATE, LD, LTOD, LTIME_OF_DAY, LDT, LDATE_AND_TIME (any case); None for others
// (INT, a type name).
LiteralFamily literalFamily(std::string_view prefix);

// `1h2m3s4ms`, `-1.5s`, `1_000ms`: the magnitude in nanoseconds (must fit in int64) and sign.
bool decodeDuration(std::string_view body, uint64_t& ns, bool& negative, LiteralError& why);
// yyyy-mm-dd (1970..9999) to seconds since 1970.
bool decodeDate(std::string_view body, int64_t& seconds, LiteralError& why);
// hh:mm[:ss[.fff]] to milliseconds since midnight.
bool decodeTimeOfDay(std::string_view body, int64_t& ms, LiteralError& why);
// yyyy-mm-dd-hh:mm:ss[.f] to seconds since 1970 (the fraction is dropped: DT counts seconds).
bool decodeDateAndTime(std::string_view body, int64_t& seconds, LiteralError& why);
// Any body of `family` to its value: TIME (truncated toward zero) and TOD in milliseconds,
// LTIME in nanoseconds, DATE and DT in seconds since 1970, LDATE and LDT in nanoseconds since
// 1970, LTOD in nanoseconds since midnight (fractions down to 1 ns). Refuses LiteralFamily::None.
bool decodeLiteralBody(std::string_view body, LiteralFamily family, int64_t& value, LiteralError& why);

// Digits of `base` (2..36, letters in either case), underscores ignored anywhere; false if
// there is no digit, a character that is not a digit of the base, or the value is beyond 64 bits.
bool parseDigits(std::string_view digits, unsigned base, uint64_t& out);
// parseDigits in base 10.
bool parseDecimal(std::string_view digits, uint64_t& out);
// The radix of a based integer (the `16` of 16#FF): true for 2, 8 and 16, the bases IEC
// 61131-3 allows; `base` is untouched otherwise.
bool parseRadix(std::string_view text, unsigned& base);

// Run-time text to a value of the family, as STRING_TO_TIME and friends read it: leading and
// trailing blanks ignored, the prefix optional (`T#1s`, `TIME#1s` or `1s`; `DT#...`). TIME and
// TOD give milliseconds, LTIME nanoseconds, DATE and DT seconds since 1970. False if malformed.
bool parseTimeOrDateText(std::string_view text, LiteralFamily family, int64_t& value);

// Run-time text to an integer: blanks, an optional sign, decimal digits or BASE#digits
// (2#, 8#, 16#; underscores ignored), an optional type prefix (`INT#5`). Digits after the
// number end it (`42abc` is 42), as CODESYS reads them; saturates at the int64 range. False if
// there is no number at all.
bool parseIntegerText(std::string_view text, int64_t& value);

}  // namespace virtcom
