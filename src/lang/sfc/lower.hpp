#pragma once
// Lowering of a Sequential Function Chart (sfc_model.hpp) into the ordinary ST of its POU.
#include <string_view>

#include "core/diagnostics.hpp"
#include "lang/sfc/sfc_model.hpp"
#include "lang/syntax/ast.hpp"

namespace virtcom::sfc {

// The struct type of a step variable (declared by the standard library prelude): `X : BOOL`
// (the step is active) and `T : TIME` (time since its last activation; kept after it ends).
inline constexpr std::string_view kStepTypeName = "SFC_STEP";

// `{attribute 'sfc_transient_chaining'}` on the POU: a call keeps evolving while transitions
// fire (through transient steps), up to as many evolutions as the chart has steps.
inline constexpr std::string_view kTransientChainingAttribute = "sfc_transient_chaining";

// Checks `chart` and, if it is sound, appends its evolution to `pou`, a PROGRAM or
// FUNCTION_BLOCK whose variables, statements and ACTIONs are already parsed:
// - every step becomes a variable `Name : SFC_STEP` (so `Name.X`, `Name.T` and
//   `MAIN.Name.X` work everywhere); the bookkeeping (transition flags, action control, time)
//   becomes hidden variables named `__sfc_...`;
// - chart.actions move into pou.actions;
// - the chart's statements go after the POU's own statements, once per call of the POU:
//   (1) the first call activates the initial step; later calls advance every active step's T,
//   evaluate every transition whose source steps are all active (on the activity at the start
//   of the call; of the transitions leaving one step only the first in priority order that is
//   clear fires) and fire the clear ones together (deactivate sources, then activate targets:
//   one evolution per call). With kTransientChainingAttribute on the POU, every call (the
//   first one too, after activating the initial step) repeats the evaluate-and-fire on the new
//   activity while a transition fired, at most once per step of the chart; (2) action control per IEC 61131-3 for the new activity, then
//   every action whose Q is set runs (and once more, with Q reset, after a non-pulse Q falls).
// A copy of the chart as written goes to pou.chart (with the ranges of statements, variable
// blocks and actions the lowering appended), so the exporter writes it as a chart.
// Reports chart errors (E401-E407) with the element's location; on any error nothing is
// appended. New nodes take ids from ++nextNodeId. Never throws on bad input.
void lowerChart(Chart chart, st::Pou& pou, Diagnostics& diags, st::NodeId& nextNodeId);

}  // namespace virtcom::sfc
