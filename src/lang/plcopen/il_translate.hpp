#pragma once
// IL (Instruction List) bodies to ST statements (docs/st-dialect.md, "PLCopen TC6 XML"):
// - The current result (CR) is carried as an ST expression, so `LD a  ADD b  ST c` becomes
//   `c := a + b;`. After `ST x` the CR is `x`. Before an instruction that could change what the
//   CR reads, or would evaluate it twice (S, R, a conditional jump, call or return), a CR that
//   is not a plain variable is held in a hidden BOOL (those instructions take a BOOL).
// - Labels cut the body into sections (jump_sections.hpp). A label whose first instruction reads
//   the CR (`QuitFb: ST Cnt`) receives it in a hidden variable of the CR's type, which must follow
//   from the declared type of an operand (the POU's variables, named global lists) or a typed
//   literal; otherwise X011.
// - Deferred operators (`AND( b ... )`) nest; `)` applies them.
// - `CAL inst(...)` calls an FB instance (`CALC`/`CALCN`: when the CR is TRUE/FALSE); after a call
//   a CR that reads the instance is undefined. Any other name as operator is a function called
//   with the CR as its first argument: `LD 0  LIMIT x, 100` is `LIMIT(0, x, 100)`. A formal call
//   `LIMIT( MN := 0, IN := x, MX := 100 )` (also over several lines; `ADD( IN1 := a, IN2 := b )`
//   too: `:=` or `=>` in the list tells it from a deferred ADD) is the call as written, and its
//   result replaces the CR.
// - The FB input operators call the FB with that input: `LD c  CLK trig` is `trig(CLK := c);`
//   (S1, R1, CLK, CU, CD, PV, IN, PT; S and R on an RS/SR instance).
// - `RET`, `RETC`, `RETCN` return; `JMP`, `JMPC`, `JMPCN` jump.
// Not translated (X011): reading a CR that no instruction set.
#include <string_view>

#include "lang/plcopen/import_internal.hpp"

namespace virtcom::plcopen::detail {

// `text` is the IL text node; hidden variables go into `owner` (names start with "__" + prefix).
st::StmtList translateIl(Importer& imp, pugi::xml_node text, st::Pou& owner, std::string_view prefix);

}  // namespace virtcom::plcopen::detail
