#pragma once
// Internal to lang/sfc: resolves a chart's names to indices and checks its structure.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostics.hpp"
#include "lang/sfc/sfc_model.hpp"

namespace virtcom::sfc::detail {

// Case-insensitive identity of an IEC name.
std::string nameKey(std::string_view name);

struct ResolvedChart {
  std::vector<size_t> initials;                 // index into Chart::steps; one per network
  std::vector<std::vector<size_t>> from, to;    // per transition: step indices
  std::vector<size_t> priorityOrder;            // transition indices, highest priority first
};

// Checks names and element forms (E401-E404, E407): duplicate or unknown steps, one initial
// step per network (the steps connected by transitions; a body may hold several), qualifiers and their durations, transition conditions. `pouActionNames` are the names
// of the POU's ACTIONs (to detect clashes with chart actions). Returns nullopt after any error.
std::optional<ResolvedChart> resolveChart(const Chart& chart, const std::vector<std::string>& pouActionNames,
                                          Diagnostics& diags);

// Explores the chart's reachable situations (sets of active steps), taking every transition
// condition as possibly true, and reports unsafe charts (E405: a transition can activate a step
// that is still active, e.g. a jump out of a parallel branch) and unreachable elements (E406:
// steps never active, transitions whose source steps are never active together, e.g. a
// simultaneous convergence of selective branches). The exploration stops after kMaxSituations
// situations or kMaxFirings transition firings (compile time stays bounded for huge charts);
// then only what was explored is checked for unsafety, and nothing is reported unreachable.
// Returns false if it reported an error.
inline constexpr size_t kMaxSituations = 20000;
inline constexpr size_t kMaxFirings = 1000000;
bool analyseChart(const Chart& chart, const ResolvedChart& resolved, Diagnostics& diags);

// E409 for every assignment (or call output `=>`) to a step flag `Step.X` / `Step.T` in the
// POU's statements, ACTIONs and METHODs and the chart's transition bodies and actions: only the
// chart sets them. Returns false if it reported an error.
bool checkStepWrites(const Chart& chart, const st::Pou& pou, Diagnostics& diags);

}  // namespace virtcom::sfc::detail
