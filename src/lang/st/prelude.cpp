#include "lang/st/prelude.hpp"

namespace virtcom::st {

// CTU/CTD/CTUD count in INT (IEC); CV keeps counting up to the type's limit (not only to PV),
// as CODESYS/TwinCAT do. F_TRIG's memory starts TRUE so a FALSE CLK on the first call is no edge.
// SFC_STEP is the type of SFC step variables (lang/sfc/lower.hpp): Step.X, Step.T.
static constexpr std::string_view kSource = R"ST(
TYPE SFC_STEP :
STRUCT
  X : BOOL;
  T : TIME;
END_STRUCT
END_TYPE

FUNCTION_BLOCK TON
VAR_INPUT IN : BOOL; PT : TIME; END_VAR
VAR_OUTPUT Q : BOOL; ET : TIME; END_VAR
VAR {attribute 'hide'} startNs : LTIME; {attribute 'hide'} running : BOOL; END_VAR
VAR_TEMP elapsed : TIME; END_VAR
IF IN THEN
  IF NOT running THEN running := TRUE; startNs := __SYSTIME_NS(); END_IF
  elapsed := LTIME_TO_TIME(__SYSTIME_NS() - startNs);
  IF elapsed >= PT THEN Q := TRUE; ET := PT; ELSE Q := FALSE; ET := elapsed; END_IF
ELSE
  running := FALSE; Q := FALSE; ET := T#0ms;
END_IF
END_FUNCTION_BLOCK

FUNCTION_BLOCK TOF
VAR_INPUT IN : BOOL; PT : TIME; END_VAR
VAR_OUTPUT Q : BOOL; ET : TIME; END_VAR
VAR {attribute 'hide'} startNs : LTIME; {attribute 'hide'} running : BOOL; END_VAR
VAR_TEMP elapsed : TIME; END_VAR
IF IN THEN
  Q := TRUE; ET := T#0ms; running := FALSE;
ELSIF Q THEN
  IF NOT running THEN running := TRUE; startNs := __SYSTIME_NS(); END_IF
  elapsed := LTIME_TO_TIME(__SYSTIME_NS() - startNs);
  IF elapsed >= PT THEN Q := FALSE; ET := PT; running := FALSE; ELSE ET := elapsed; END_IF
END_IF
END_FUNCTION_BLOCK

FUNCTION_BLOCK TP
VAR_INPUT IN : BOOL; PT : TIME; END_VAR
VAR_OUTPUT Q : BOOL; ET : TIME; END_VAR
VAR {attribute 'hide'} startNs : LTIME; {attribute 'hide'} running : BOOL; {attribute 'hide'} prevIn : BOOL; END_VAR
VAR_TEMP elapsed : TIME; END_VAR
IF NOT running AND IN AND NOT prevIn THEN
  running := TRUE; startNs := __SYSTIME_NS(); Q := TRUE;
END_IF
IF running THEN
  elapsed := LTIME_TO_TIME(__SYSTIME_NS() - startNs);
  IF elapsed >= PT THEN Q := FALSE; ET := PT; running := FALSE; ELSE ET := elapsed; END_IF
END_IF
IF NOT running AND NOT IN THEN ET := T#0ms; END_IF
prevIn := IN;
END_FUNCTION_BLOCK

FUNCTION_BLOCK CTU
VAR_INPUT CU : BOOL; RESET : BOOL; PV : INT; END_VAR
VAR_OUTPUT Q : BOOL; CV : INT; END_VAR
VAR {attribute 'hide'} prevCU : BOOL; END_VAR
IF RESET THEN CV := 0;
ELSIF CU AND NOT prevCU AND CV < 32767 THEN CV := CV + 1;
END_IF
Q := CV >= PV;
prevCU := CU;
END_FUNCTION_BLOCK

FUNCTION_BLOCK CTD
VAR_INPUT CD : BOOL; LOAD : BOOL; PV : INT; END_VAR
VAR_OUTPUT Q : BOOL; CV : INT; END_VAR
VAR {attribute 'hide'} prevCD : BOOL; END_VAR
IF LOAD THEN CV := PV;
ELSIF CD AND NOT prevCD AND CV > -32768 THEN CV := CV - 1;
END_IF
Q := CV <= 0;
prevCD := CD;
END_FUNCTION_BLOCK

FUNCTION_BLOCK CTUD
VAR_INPUT CU : BOOL; CD : BOOL; RESET : BOOL; LOAD : BOOL; PV : INT; END_VAR
VAR_OUTPUT QU : BOOL; QD : BOOL; CV : INT; END_VAR
VAR {attribute 'hide'} prevCU : BOOL; {attribute 'hide'} prevCD : BOOL; END_VAR
IF RESET THEN CV := 0;
ELSIF LOAD THEN CV := PV;
ELSE
  IF CU AND NOT prevCU AND CV < 32767 THEN CV := CV + 1; END_IF
  IF CD AND NOT prevCD AND CV > -32768 THEN CV := CV - 1; END_IF
END_IF
QU := CV >= PV;
QD := CV <= 0;
prevCU := CU;
prevCD := CD;
END_FUNCTION_BLOCK

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

std::string_view standardLibrarySource() { return kSource; }

}  // namespace virtcom::st
