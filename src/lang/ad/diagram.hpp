#pragma once
// The activity-diagram model (seed 002): a program of BOOL ports (the seed's I/O/M port types)
// and one or more diagrams, each one function of the control logic. Produced by the reader
// (reader.hpp), decomposed into logic units and rules (decompose.hpp), lowered to ST (lower.hpp).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/source.hpp"

namespace virtcom::ad {

enum class NodeKind : uint8_t {
#define AD_NODE(kind, keyword, isBar) kind,
#include "lang/ad/elements.def"
};

enum class ArcKind : uint8_t {
#define AD_ARC(kind, arrow, tableName) kind,
#include "lang/ad/elements.def"
};

enum class BlockType : uint8_t {
#define AD_BLOCK(type, isTimer, drivenInput, resetInput) type,
#include "lang/ad/elements.def"
};

// The seed's port types: input (sensors), output (actuators), internal memory.
enum class PortKind : uint8_t { Input, Output, Memory };

struct Port {
  std::string name;
  PortKind kind = PortKind::Memory;
  std::string address;  // "%IX0.0"; empty: an ordinary variable of the program
  SourceLocation loc;
};

struct Node {
  NodeKind kind = NodeKind::Activity;
  std::string id;
  std::string variable;        // Activity: a port, a located address (%IX0.0) or an outside variable
  BlockType block = BlockType::TON;  // Timer, Counter
  std::string blockType;       // Block: the function block type (an ST FUNCTION_BLOCK, a library FB)
  std::string blockIn = "IN", blockOut = "Q";  // Block: the BOOL input a rule drives, the output it reads
  int64_t presetNs = 0;        // Timer: PT
  uint64_t presetCount = 0;    // Counter: PV
  SourceLocation loc;
};

struct Arc {
  ArcKind kind = ArcKind::Normal;
  size_t from = 0, to = 0;  // indexes into Diagram::nodes
  SourceLocation loc;
};

struct Diagram {
  std::string name;
  SourceLocation loc;
  std::vector<Node> nodes;
  std::vector<Arc> arcs;  // in the order written: the order of the logic units and rules
};

struct Program {
  std::string name;
  SourceLocation loc;
  std::vector<Port> ports;
  std::vector<Diagram> diagrams;
};

std::string_view nodeKeyword(NodeKind kind);
bool isBar(NodeKind kind);  // OR-join, AND-join, AND-split
bool isJoin(NodeKind kind);
// Start and stop only mark where a diagram begins and ends; they take part in no logic unit.
inline bool isTerminal(NodeKind kind) { return kind == NodeKind::Start || kind == NodeKind::Stop; }
// Timers, counters and other function blocks: elements that are FB instances (LU type 3).
inline bool isBlock(NodeKind kind) {
  return kind == NodeKind::Timer || kind == NodeKind::Counter || kind == NodeKind::Block;
}
std::string_view arcArrow(ArcKind kind);
std::string_view arcTableName(ArcKind kind);
std::string_view blockTypeName(BlockType type);
bool isTimerBlock(BlockType type);
// The block input a rule drives: `on` (normal arc) IN, CU or CD; else (NOT-OUT) RESET or LOAD.
std::string_view blockInput(BlockType type, bool on);
std::optional<NodeKind> nodeKindFromKeyword(std::string_view keyword);

// The same for a block element (isBlock): its FB type, the input a rule drives (`on`) or
// resets (NOT-OUT; empty if it has none, as timers and other FBs), and the BOOL output that is
// its state (Q).
std::string_view blockTypeOf(const Node& block);
std::string_view blockInputOf(const Node& block, bool on);
std::string_view blockOutputOf(const Node& block);
std::optional<ArcKind> arcKindFromArrow(std::string_view arrow);
std::optional<ArcKind> arcKindFromTableName(std::string_view name);  // "normal", "NOT-IN", "NOT-OUT", any case
std::optional<BlockType> blockTypeFromName(std::string_view name);  // any case

// The port kind of an activity: its port's, or the area of its address (%I, %Q, %M);
// nullopt for an outside variable.
std::optional<PortKind> activityPortKind(const Program& program, const Node& activity);
// The port named `name` (exact spelling, ASCII case-insensitive as ST names are), or null.
const Port* findPort(const Program& program, std::string_view name);

}  // namespace virtcom::ad
