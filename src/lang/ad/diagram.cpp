#include "lang/ad/diagram.hpp"

#include <cctype>

namespace virtcom::ad {

namespace {

struct NodeInfo {
  std::string_view keyword;
  bool bar;
};
constexpr NodeInfo kNodes[] = {
#define AD_NODE(kind, keyword, isBar) {keyword, isBar},
#include "lang/ad/elements.def"
};

struct ArcInfo {
  std::string_view arrow, tableName;
};
constexpr ArcInfo kArcs[] = {
#define AD_ARC(kind, arrow, tableName) {arrow, tableName},
#include "lang/ad/elements.def"
};

struct BlockInfo {
  std::string_view name;
  bool timer;
  std::string_view drivenInput, resetInput;
};
constexpr BlockInfo kBlocks[] = {
#define AD_BLOCK(type, isTimer, drivenInput, resetInput) {#type, isTimer, drivenInput, resetInput},
#include "lang/ad/elements.def"
};

bool sameName(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
  return true;
}

}  // namespace

std::string_view nodeKeyword(NodeKind kind) { return kNodes[static_cast<size_t>(kind)].keyword; }
bool isBar(NodeKind kind) { return kNodes[static_cast<size_t>(kind)].bar; }
bool isJoin(NodeKind kind) { return kind == NodeKind::OrJoin || kind == NodeKind::AndJoin; }
std::string_view arcArrow(ArcKind kind) { return kArcs[static_cast<size_t>(kind)].arrow; }
std::string_view arcTableName(ArcKind kind) { return kArcs[static_cast<size_t>(kind)].tableName; }
std::string_view blockTypeName(BlockType type) { return kBlocks[static_cast<size_t>(type)].name; }
bool isTimerBlock(BlockType type) { return kBlocks[static_cast<size_t>(type)].timer; }
std::string_view blockInput(BlockType type, bool on) {
  const BlockInfo& info = kBlocks[static_cast<size_t>(type)];
  return on ? info.drivenInput : info.resetInput;
}

std::string_view blockTypeOf(const Node& block) {
  return block.kind == NodeKind::Block ? std::string_view(block.blockType) : blockTypeName(block.block);
}

std::string_view blockInputOf(const Node& block, bool on) {
  if (block.kind != NodeKind::Block) return blockInput(block.block, on);
  return on ? std::string_view(block.blockIn) : std::string_view();
}

std::string_view blockOutputOf(const Node& block) {
  return block.kind == NodeKind::Block ? std::string_view(block.blockOut) : std::string_view("Q");
}

std::optional<NodeKind> nodeKindFromKeyword(std::string_view keyword) {
  for (size_t i = 0; i < std::size(kNodes); ++i)
    if (sameName(kNodes[i].keyword, keyword)) return static_cast<NodeKind>(i);
  return std::nullopt;
}

std::optional<ArcKind> arcKindFromArrow(std::string_view arrow) {
  for (size_t i = 0; i < std::size(kArcs); ++i)
    if (kArcs[i].arrow == arrow) return static_cast<ArcKind>(i);
  return std::nullopt;
}

std::optional<ArcKind> arcKindFromTableName(std::string_view name) {
  for (size_t i = 0; i < std::size(kArcs); ++i)
    if (sameName(kArcs[i].tableName, name)) return static_cast<ArcKind>(i);
  return std::nullopt;
}

std::optional<BlockType> blockTypeFromName(std::string_view name) {
  for (size_t i = 0; i < std::size(kBlocks); ++i)
    if (sameName(kBlocks[i].name, name)) return static_cast<BlockType>(i);
  return std::nullopt;
}

const Port* findPort(const Program& program, std::string_view name) {
  for (const Port& port : program.ports)
    if (sameName(port.name, name)) return &port;
  return nullptr;
}

std::optional<PortKind> activityPortKind(const Program& program, const Node& activity) {
  if (const Port* port = findPort(program, activity.variable)) return port->kind;
  if (activity.variable.size() < 2 || activity.variable[0] != '%') return std::nullopt;
  switch (std::toupper(static_cast<unsigned char>(activity.variable[1]))) {
    case 'I': return PortKind::Input;
    case 'Q': return PortKind::Output;
    case 'M': return PortKind::Memory;
    default: return std::nullopt;
  }
}

}  // namespace virtcom::ad
