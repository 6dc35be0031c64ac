#include "lang/st/prelude.hpp"

#include <string>

namespace virtcom::st {

// F_TRIG's memory starts TRUE so a FALSE CLK on the first call is no edge.
// SFC_STEP is the type of SFC step variables (lang/sfc/lower.hpp): Step.X, Step.T.
static constexpr std::string_view kSource = R"ST(
TYPE SFC_STEP :
STRUCT
  X : BOOL;
  T : TIME;
END_STRUCT
END_TYPE

FUNCTION_BLOCK R_TRIG
VAR_INPUT CLK : BOOL; END_VAR
VAR_OUTPUT Q : BOOL; END_VAR
VAR {attribute 'hide'} M : BOOL; END_VAR
Q := CLK AND NOT M;
M := CLK;
END_FUNCTION_BLOCK

FUNCTION_BLOCK F_TRIG
VAR_INPUT CLK : BOOL; END_VAR
VAR_OUTPUT Q : BOOL; END_VAR
VAR {attribute 'hide'} M : BOOL := TRUE; END_VAR
Q := NOT CLK AND NOT M;
M := NOT CLK;
END_FUNCTION_BLOCK

FUNCTION_BLOCK SR
VAR_INPUT SET1 : BOOL; RESET : BOOL; END_VAR
VAR_OUTPUT Q1 : BOOL; END_VAR
Q1 := SET1 OR (NOT RESET AND Q1);
END_FUNCTION_BLOCK

FUNCTION_BLOCK RS
VAR_INPUT SET : BOOL; RESET1 : BOOL; END_VAR
VAR_OUTPUT Q1 : BOOL; END_VAR
Q1 := NOT RESET1 AND (SET OR Q1);
END_FUNCTION_BLOCK
)ST";

namespace {

// CTU/CTD/CTUD count in INT (IEC); CV keeps counting up to the type's limit (not only to PV),
// as CODESYS/TwinCAT do. The typed counters of IEC 61131-3 ed. 3 (CTU_DINT, CTD_UDINT, ...)
// are the same FBs with PV and CV of another type: one text, so they cannot drift apart.
// @N is the FB name's suffix, @T the count type, @MIN/@MAX its range as typed literals.
constexpr std::string_view kCounters = R"ST(
FUNCTION_BLOCK CTU@N
VAR_INPUT CU : BOOL; RESET : BOOL; PV : @T; END_VAR
VAR_OUTPUT Q : BOOL; CV : @T; END_VAR
VAR {attribute 'hide'} prevCU : BOOL; END_VAR
IF RESET THEN CV := 0;
ELSIF CU AND NOT prevCU AND CV < @MAX THEN CV := CV + 1;
END_IF
Q := CV >= PV;
prevCU := CU;
END_FUNCTION_BLOCK

FUNCTION_BLOCK CTD@N
VAR_INPUT CD : BOOL; LOAD : BOOL; PV : @T; END_VAR
VAR_OUTPUT Q : BOOL; CV : @T; END_VAR
VAR {attribute 'hide'} prevCD : BOOL; END_VAR
IF LOAD THEN CV := PV;
ELSIF CD AND NOT prevCD AND CV > @MIN THEN CV := CV - 1;
END_IF
Q := CV <= 0;
prevCD := CD;
END_FUNCTION_BLOCK

FUNCTION_BLOCK CTUD@N
VAR_INPUT CU : BOOL; CD : BOOL; RESET : BOOL; LOAD : BOOL; PV : @T; END_VAR
VAR_OUTPUT QU : BOOL; QD : BOOL; CV : @T; END_VAR
VAR {attribute 'hide'} prevCU : BOOL; {attribute 'hide'} prevCD : BOOL; END_VAR
IF RESET THEN CV := 0;
ELSIF LOAD THEN CV := PV;
ELSE
  IF CU AND NOT prevCU AND CV < @MAX THEN CV := CV + 1; END_IF
  IF CD AND NOT prevCD AND CV > @MIN THEN CV := CV - 1; END_IF
END_IF
QU := CV >= PV;
QD := CV <= 0;
prevCU := CU;
prevCD := CD;
END_FUNCTION_BLOCK
)ST";

std::string replaceAll(std::string text, std::string_view from, std::string_view to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

std::string counters() {
  struct Variant {
    std::string_view suffix, type, min, max;
  };
  static constexpr Variant kVariants[] = {
      {"", "INT", "INT#-32768", "INT#32767"},
      {"_INT", "INT", "INT#-32768", "INT#32767"},
      {"_DINT", "DINT", "DINT#-2147483648", "DINT#2147483647"},
      {"_LINT", "LINT", "LINT#-9223372036854775808", "LINT#9223372036854775807"},
      {"_UDINT", "UDINT", "UDINT#0", "UDINT#4294967295"},
      {"_ULINT", "ULINT", "ULINT#0", "ULINT#18446744073709551615"},
  };
  std::string out;
  for (const Variant& v : kVariants) {
    std::string text = replaceAll(std::string(kCounters), "@N", v.suffix);
    text = replaceAll(std::move(text), "@T", v.type);
    text = replaceAll(std::move(text), "@MIN", v.min);
    out += replaceAll(std::move(text), "@MAX", v.max);
  }
  return out;
}

// TON/TOF/TP, and the LTIME timers LTON/LTOF/LTP of IEC 61131-3 ed. 3 (CODESYS, Tc2_Standard):
// one text, so they cannot drift apart. @N is the name's prefix, @T the time type, @ELAPSED the
// time since startNs in @T, @ZERO its zero.
constexpr std::string_view kTimers = R"ST(
FUNCTION_BLOCK @NTON
VAR_INPUT IN : BOOL; PT : @T; END_VAR
VAR_OUTPUT Q : BOOL; ET : @T; END_VAR
VAR {attribute 'hide'} startNs : LTIME; {attribute 'hide'} running : BOOL; END_VAR
VAR_TEMP elapsed : @T; END_VAR
IF IN THEN
  IF NOT running THEN running := TRUE; startNs := __SYSTIME_NS(); END_IF
  elapsed := @ELAPSED;
  IF elapsed >= PT THEN Q := TRUE; ET := PT; ELSE Q := FALSE; ET := elapsed; END_IF
ELSE
  running := FALSE; Q := FALSE; ET := @ZERO;
END_IF
END_FUNCTION_BLOCK

FUNCTION_BLOCK @NTOF
VAR_INPUT IN : BOOL; PT : @T; END_VAR
VAR_OUTPUT Q : BOOL; ET : @T; END_VAR
VAR {attribute 'hide'} startNs : LTIME; {attribute 'hide'} running : BOOL; END_VAR
VAR_TEMP elapsed : @T; END_VAR
IF IN THEN
  Q := TRUE; ET := @ZERO; running := FALSE;
ELSIF Q THEN
  IF NOT running THEN running := TRUE; startNs := __SYSTIME_NS(); END_IF
  elapsed := @ELAPSED;
  IF elapsed >= PT THEN Q := FALSE; ET := PT; running := FALSE; ELSE ET := elapsed; END_IF
END_IF
END_FUNCTION_BLOCK

FUNCTION_BLOCK @NTP
VAR_INPUT IN : BOOL; PT : @T; END_VAR
VAR_OUTPUT Q : BOOL; ET : @T; END_VAR
VAR {attribute 'hide'} startNs : LTIME; {attribute 'hide'} running : BOOL; {attribute 'hide'} prevIn : BOOL; END_VAR
VAR_TEMP elapsed : @T; END_VAR
IF NOT running AND IN AND NOT prevIn THEN
  running := TRUE; startNs := __SYSTIME_NS(); Q := TRUE;
END_IF
IF running THEN
  elapsed := @ELAPSED;
  IF elapsed >= PT THEN Q := FALSE; ET := PT; running := FALSE; ELSE ET := elapsed; END_IF
END_IF
IF NOT running AND NOT IN THEN ET := @ZERO; END_IF
prevIn := IN;
END_FUNCTION_BLOCK

)ST";

std::string timers() {
  struct Variant {
    std::string_view prefix, type, elapsed, zero;
  };
  static constexpr Variant kVariants[] = {
      {"", "TIME", "LTIME_TO_TIME(__SYSTIME_NS() - startNs)", "T#0ms"},
      {"L", "LTIME", "(__SYSTIME_NS() - startNs)", "LTIME#0ns"},
  };
  std::string out;
  for (const Variant& v : kVariants) {
    std::string text = replaceAll(std::string(kTimers), "@N", v.prefix);
    text = replaceAll(std::move(text), "@T", v.type);
    text = replaceAll(std::move(text), "@ELAPSED", v.elapsed);
    out += replaceAll(std::move(text), "@ZERO", v.zero);
  }
  return out;
}

// BCD conversions of IEC 61131-3 ed. 3 (WORD_BCD_TO_UINT, UINT_TO_BCD_WORD, ...), one text for
// the four widths. A nibble above 9 is taken at its value (no error); digits that do not fit
// the bit string are dropped.
constexpr std::string_view kBcd = R"ST(
FUNCTION @B_BCD_TO_@U : @U
VAR_INPUT IN : @B; END_VAR
VAR i : INT; weight : @U := 1; END_VAR
FOR i := 0 TO @DIGITS - 1 DO
  @B_BCD_TO_@U := @B_BCD_TO_@U + @B_TO_@U(SHR(IN, 4 * i) AND 16#F) * weight;
  weight := weight * 10;
END_FOR
END_FUNCTION

FUNCTION @U_TO_BCD_@B : @B
VAR_INPUT IN : @U; END_VAR
VAR i : INT; rest : @U; END_VAR
rest := IN;
FOR i := 0 TO @DIGITS - 1 DO
  @U_TO_BCD_@B := @U_TO_BCD_@B OR SHL(@U_TO_@B(rest MOD 10), 4 * i);
  rest := rest / 10;
END_FOR
END_FUNCTION
)ST";

std::string bcdConversions() {
  struct Variant {
    std::string_view bits, number, digits;
  };
  static constexpr Variant kVariants[] = {
      {"BYTE", "USINT", "2"}, {"WORD", "UINT", "4"}, {"DWORD", "UDINT", "8"}, {"LWORD", "ULINT", "16"}};
  std::string out;
  for (const Variant& v : kVariants) {
    std::string text = replaceAll(std::string(kBcd), "@B", v.bits);
    text = replaceAll(std::move(text), "@U", v.number);
    out += replaceAll(std::move(text), "@DIGITS", v.digits);
  }
  return out;
}

// The IEC 61131-3 time functions (table 30): the ST operators on TIME, DATE, TOD and DT under
// their function names. MUL_TIME and DIV_TIME take any number as LREAL and round the result
// to the millisecond, as `TIME * LREAL` does.
std::string timeFunctions() {
  struct Row {
    std::string_view name, result, in1, in2, op;
  };
  static constexpr Row kRows[] = {
      {"ADD_TIME", "TIME", "TIME", "TIME", "+"},       {"ADD_LTIME", "LTIME", "LTIME", "LTIME", "+"},
      {"ADD_TOD_TIME", "TOD", "TOD", "TIME", "+"},     {"ADD_DT_TIME", "DT", "DT", "TIME", "+"},
      {"SUB_TIME", "TIME", "TIME", "TIME", "-"},       {"SUB_LTIME", "LTIME", "LTIME", "LTIME", "-"},
      {"SUB_DATE_DATE", "TIME", "DATE", "DATE", "-"},  {"SUB_TOD_TIME", "TOD", "TOD", "TIME", "-"},
      {"SUB_TOD_TOD", "TIME", "TOD", "TOD", "-"},      {"SUB_DT_TIME", "DT", "DT", "TIME", "-"},
      {"SUB_DT_DT", "TIME", "DT", "DT", "-"},          {"MUL_TIME", "TIME", "TIME", "LREAL", "*"},
      {"MUL_LTIME", "LTIME", "LTIME", "LREAL", "*"},   {"DIV_TIME", "TIME", "TIME", "LREAL", "/"},
      {"DIV_LTIME", "LTIME", "LTIME", "LREAL", "/"},
      // IEC 61131-3 ed. 3: the same on the long types, in nanoseconds
      {"ADD_LTOD_LTIME", "LTOD", "LTOD", "LTIME", "+"}, {"ADD_LDT_LTIME", "LDT", "LDT", "LTIME", "+"},
      {"SUB_LDATE_LDATE", "LTIME", "LDATE", "LDATE", "-"}, {"SUB_LTOD_LTIME", "LTOD", "LTOD", "LTIME", "-"},
      {"SUB_LTOD_LTOD", "LTIME", "LTOD", "LTOD", "-"}, {"SUB_LDT_LTIME", "LDT", "LDT", "LTIME", "-"},
      {"SUB_LDT_LDT", "LTIME", "LDT", "LDT", "-"},
  };
  std::string out;
  for (const Row& r : kRows) {
    std::string name(r.name);
    out += "\nFUNCTION " + name + " : " + std::string(r.result) + "\nVAR_INPUT IN1 : " + std::string(r.in1) +
           "; IN2 : " + std::string(r.in2) + "; END_VAR\n" + name + " := IN1 " + std::string(r.op) +
           " IN2;\nEND_FUNCTION\n";
  }
  // DT from a DATE and a TOD (the TOD's fraction of a second is dropped, as DT has none).
  out += R"ST(
FUNCTION CONCAT_DATE_TOD : DT
VAR_INPUT IN1 : DATE; IN2 : TOD; END_VAR
CONCAT_DATE_TOD := DATE_TO_DT(IN1) + TOD_TO_TIME(IN2);
END_FUNCTION
FUNCTION CONCAT_LDATE_LTOD : LDT
VAR_INPUT IN1 : LDATE; IN2 : LTOD; END_VAR
CONCAT_LDATE_LTOD := LDATE_TO_LDT(IN1) + LTOD_TO_LTIME(IN2);
END_FUNCTION
)ST";
  return out;
}

}  // namespace

std::string_view standardLibrarySource() {
  static const std::string source = std::string(kSource) + timers() + counters() + bcdConversions() + timeFunctions();
  return source;
}

}  // namespace virtcom::st
