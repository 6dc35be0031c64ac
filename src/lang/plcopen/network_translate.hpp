#pragma once
// LD and FBD bodies to ST statements (see docs/st-dialect.md, "PLCopen XML"):
// - Statement elements (coils, output and in-out variables, blocks, jumps, returns, labels) run in
//   executionOrderId order, then top to bottom and left to right by position, then document order;
//   an element's inputs are evaluated first (each block runs once per scan). A connection back to
//   a block that is still being evaluated is a feedback path and reads the previous scan's value.
// - Contacts AND the power flow with their variable; several connections into one input are the
//   OR of parallel branches. Edge contacts and coils, and edge block inputs, keep the previous
//   value in a hidden BOOL variable of the POU; results used by several elements are held in
//   hidden VAR_TEMP variables, so each element is evaluated once.
// - Function blocks are called with their connected inputs; functions are inlined where their
//   result is used. EN gates the call (FB) or the assignments using the result (function).
// - Labels split the body into sections; jumps restart a loop at the section of their label.
#include <string_view>

#include "lang/plcopen/import_internal.hpp"
#include "lang/plcopen/network.hpp"

namespace virtcom::plcopen::detail {

Network readNetwork(Importer& imp, pugi::xml_node body, bool ladder);
// The LD/FBD elements of an SFC body and the transitions whose condition they feed (a
// `Condition` element with the transition's localId).
Network readChartNetwork(Importer& imp, pugi::xml_node sfc);
// True for the element names of LD and FBD bodies (contact, block, inVariable, ...).
bool isNetworkElement(std::string_view element);

// Translates the network; hidden variables go into `owner` (names start with "__" + prefix).
st::StmtList translateNetwork(Importer& imp, const Network& net, st::Pou& owner, std::string_view prefix);

// The value wired into the condition of transition `transitionId` of a chart network, as an
// expression; the statements it needs first (FB calls, edge memories, shared values) go to
// `before`. Hidden variables as for translateNetwork.
st::ExprPtr translateCondition(Importer& imp, const Network& net, uint32_t transitionId, st::Pou& owner,
                               std::string_view prefix, st::StmtList& before);

}  // namespace virtcom::plcopen::detail
