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

// Translates the network; hidden variables go into `owner` (names start with "__" + prefix).
st::StmtList translateNetwork(Importer& imp, const Network& net, st::Pou& owner, std::string_view prefix);

}  // namespace virtcom::plcopen::detail
