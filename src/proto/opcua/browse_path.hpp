#pragma once
// Browse paths as an integrator writes them in a cell file instead of a node id (docs/opcua.md,
// The client bridge: browse paths): the text form of a RelativePath (OPC 10000-4 Annex A.2)
// from the Objects folder, e.g. "/4:MAIN/4:Clamp/4:execute" or "/3:PLC_1/3:DataBlocksGlobal/3:DB1.3:start".
//  - "/" follows a hierarchical reference (Organizes, HasComponent, ...), "." an aggregate
//    (HasComponent, HasProperty), both with their subtypes;
//  - a browse name is "NS:NAME" (NS its namespace index) or "NAME" in namespace 0;
//  - "&" escapes the next character: "&/", "&.", "&:", "&&", ... ("/4:a&.b" is the name "a.b").
// Reference types in "<...>" are not supported: a server's structure is reached by "/" and ".".
#include <expected>
#include <string>
#include <string_view>
#include <vector>

#include "proto/opcua/binary_codec.hpp"
#include "proto/opcua/types.hpp"

namespace virtcom::proto::opcua {

struct BrowsePathElement {
  bool aggregates = false;  // "." (Aggregates); else "/" (HierarchicalReferences)
  QualifiedName name;
};

// The cell file writes a browse path where it writes a node id: a path begins with "/" or ".".
bool isBrowsePath(std::string_view text);

// The elements of `text`, or what is wrong with it: which character, and the expected form.
std::expected<std::vector<BrowsePathElement>, std::string> parseBrowsePath(std::string_view text);

// A BrowsePath (OPC 10000-4 §7.6: StartingNode, RelativePath) from the Objects folder, as a
// TranslateBrowsePathsToNodeIds request carries it.
void encodeBrowsePath(Writer& w, const std::vector<BrowsePathElement>& path);

}  // namespace virtcom::proto::opcua
