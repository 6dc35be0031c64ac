#pragma once
// A diagram's rule table as ladder rungs (IEC 61131-3 LD), one rung per rule as seed 002 draws
// an LU: the IF as contacts (normal: `A=on`, normally closed: `A=off`; AND in series, OR as
// parallel branches), the THEN as coils (set for `B=on`, reset for `B=off`, as a rule latches its
// outputs) and the timers and counters it drives as function blocks in the rung. lowerProgram
// keeps the rungs on each diagram's ACTION (st::Pou::ladder) for the PLCopen LD export.
#include "lang/ad/decompose.hpp"
#include "lang/syntax/ladder.hpp"

namespace virtcom::ad {

// Per rule, in rule order: one rung per group it computes first (`Group K`: a normal coil on
// K), then the rule's rung (`Rule 3`). A counter reset (NOT-OUT into a counter) is a normal coil
// on C.RESET (C.LOAD), driven every scan as the ST lowering drives it.
st::Ladder ladderOf(const Diagram& diagram, const DiagramTables& tables);

}  // namespace virtcom::ad
