#pragma once
// A graphical body (LD or FBD) as read from the XML: elements by localId and the connections
// between their pins. network_read.cpp builds it; network_translate.cpp turns it into ST. The
// LD/FBD elements of an SFC body, which compute transition conditions, are a network too.
#include <pugixml.hpp>

#include <cstdint>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

namespace virtcom::plcopen::detail {

enum class ElementKind : uint8_t {
  LeftRail, RightRail, Contact, Coil, InVariable, OutVariable, InOutVariable, Block,
  Connector, Continuation, Jump, Label, Return, Comment,
  Condition,  // an SFC transition's <condition><connectionPointIn>: reads one value, runs nothing
};

enum class Edge : uint8_t { None, Rising, Falling };
enum class Storage : uint8_t { None, Set, Reset };

// One <connection refLocalId="..." formalParameter="..."/>: the output it reads.
struct Connection {
  uint32_t refLocalId = 0;
  std::string formal;  // which output of a block; empty for single-output elements
  pugi::xml_node node;
};

// A <connectionPointIn> (and, for blocks, the <variable> around it). Several connections are
// the wired OR of parallel LD branches.
struct Pin {
  std::string formal;  // block parameter name; empty elsewhere
  std::vector<Connection> sources;
  bool negated = false;
  Edge edge = Edge::None;
  pugi::xml_node node;
};

struct BlockOutput {
  std::string formal;
  bool negated = false;
  bool inOut = false;  // the output side of a VAR_IN_OUT: the variable passed in
};

struct Element {
  ElementKind kind = ElementKind::Comment;
  uint32_t localId = 0;
  pugi::xml_node node;
  uint32_t executionOrder = 0;  // executionOrderId; 0: not given
  bool positioned = false;
  double x = 0, y = 0;
  std::vector<Pin> inputs;       // block: inputs then in-outs; others: their connectionPointIn(s)
  std::vector<BlockOutput> outputs;  // blocks only
  bool negated = false;           // inOutVariable: its input (negatedIn)
  bool negatedOut = false;        // inOutVariable: its output
  Edge edge = Edge::None;
  Storage storage = Storage::None;
  std::string name;          // label/jump target, connector/continuation name, block typeName
  std::string instanceName;  // blocks: the FB instance; empty for functions
  size_t consumers = 0;      // connections reading this element (continuations count for their connector)
};

inline constexpr size_t kNoElement = std::numeric_limits<size_t>::max();

struct Network {
  bool ladder = false;  // LD (power flow) rather than FBD
  bool inChart = false;  // the LD/FBD elements of an SFC body (which reports its own elements)
  std::vector<Element> elements;  // document order
  std::unordered_map<uint32_t, size_t> byLocalId;  // localId -> index into elements

  size_t find(uint32_t localId) const {
    auto it = byLocalId.find(localId);
    return it == byLocalId.end() ? kNoElement : it->second;
  }
};

}  // namespace virtcom::plcopen::detail
