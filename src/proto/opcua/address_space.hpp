#pragma once
// The nodes the server serves (docs/opcua.md, What is served): the standard nodes clients read on
// connect (Root, Objects, Types, Views, Server with ServerStatus, NamespaceArray, ServerArray) and
// the PLC's variables, generated from the ADS SymbolTable: Objects → a folder per POU or GVL →
// a variable per symbol, structs as objects of variables, arrays of elementary types as array
// values; and, serving a cell, Objects → Devices → an object per device → its signals. Built
// once at start; read only afterwards (no lock needed to browse it).
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "proto/ads/symbol_table.hpp"
#include "proto/opcua/types.hpp"

namespace virtcom::proto::opcua {

enum class NodeClass : uint32_t { Object = 1, Variable = 2, DataType = 64 };

// Where a variable's value comes from.
enum class ValueSource : uint8_t {
  Fixed,          // a constant Variant (NamespaceArray, ServerArray, ...)
  Plc,            // bytes of the PLC's memory image (PlcValue)
  CurrentTime,    // the server's clock
  StartTime,
  ServerState,    // 0: Running
  ServerStatus,   // the ServerStatusDataType structure
};

// A PLC variable's place in the memory image and how its bytes read as OPC UA values.
struct PlcValue {
  BuiltinType type = BuiltinType::Null;
  uint32_t offset = 0;          // byte offset in the image (the data area)
  uint32_t elementSize = 0;     // bytes per element (STRING(n): n + 1)
  uint32_t count = 1;           // elements (1 for scalars)
  int8_t bit = -1;              // a single bit of the byte at `offset` (%IX, %QX, %MX)
  bool wide = false;            // WSTRING: UTF-16 in the image
  bool isArray = false;
  std::vector<uint32_t> dims;   // array dimensions (rank 1 or more)
};

struct Reference {
  uint32_t type = 0;   // a reference type id (ns=0)
  uint32_t target = 0; // a node index
  bool forward = true;
};

struct Node {
  NodeId id;
  NodeClass nodeClass = NodeClass::Object;
  QualifiedName browseName;
  std::string displayName, description;
  uint32_t typeDefinition = 0;  // ns=0 id of its type definition
  std::vector<Reference> references;
  // Variables only:
  ValueSource source = ValueSource::Fixed;
  Variant fixed;
  PlcValue plc;
  NodeId dataType;
  int32_t valueRank = -1;  // -1 scalar, n: n dimensions
  bool writable = false;
};

// Access level bits (OPC 10000-3 §8.57).
inline constexpr uint8_t kAccessRead = 0x01, kAccessWrite = 0x02;

// A value outside the PLC's memory, served read only (a cell device's signal): `size` bytes
// at `offset` of the image's extra part, which follows the PLC's data area.
struct ExtraVariable {
  std::string name;
  BuiltinType type = BuiltinType::Null;
  uint32_t offset = 0, size = 0;
};
// An object of such values (a cell device) in Objects/Devices, ns=4;s=|dev|<application>.<name>.
struct ExtraObject {
  std::string name;
  std::vector<ExtraVariable> variables;
};

struct AddressSpaceConfig {
  std::string applicationName = "virtcom";  // CODESYS' device name in |var|<name>.Application...
  std::string applicationUri = "urn:virtcom:plc";
  std::vector<ExtraObject> devices;         // the cell's devices; none without a cell
  uint32_t extraBytes = 0;                  // the image's extra part (every ExtraVariable fits in it)
};

class AddressSpace {
 public:
  AddressSpace(const ads::SymbolTable& table, const AddressSpaceConfig& config);

  // The node's index, or nullopt. Allocates nothing for numeric ids.
  std::optional<uint32_t> find(const NodeId& id) const;
  const Node& node(uint32_t index) const { return nodes_[index]; }
  size_t size() const { return nodes_.size(); }
  // The namespace table (index 0: OPC UA's, 1: the server's, ... 4: the PLC's).
  const std::vector<std::string>& namespaces() const { return namespaces_; }
  // "|var|virtcom.Application.MAIN.x": the CODESYS string id of a PLC path.
  std::string plcNodeName(std::string_view path) const;

 private:
  uint32_t add(Node n);
  void link(uint32_t from, uint32_t type, uint32_t to);
  void addStandardNodes();
  uint32_t folderFor(std::string_view pou);
  // Adds a variable (or an object of members for a struct) named `name` under `parent`.
  void addPlcVariable(uint32_t parent, const std::string& path, std::string_view name, const std::string& type,
                      uint32_t offset, const ads::Symbol* symbol);
  void addDevices();

  const ads::SymbolTable& table_;
  AddressSpaceConfig config_;
  std::vector<Node> nodes_;
  std::vector<std::string> namespaces_;
  std::unordered_map<uint32_t, uint32_t> numeric_;    // ns=0 numeric id -> index
  std::unordered_map<std::string, uint32_t> named_;   // ns=4 string id -> index
  std::unordered_map<std::string, uint32_t> folders_; // POU / GVL name -> folder index
};

// The built-in type an ADS type id reads as (docs/opcua.md, Data types); Null if not served.
BuiltinType builtinOf(uint32_t adsType);

// True if reference type `type` is `base` or (with subtypes) one of its subtypes.
bool isReferenceSubtype(uint32_t type, uint32_t base, bool includeSubtypes);

}  // namespace virtcom::proto::opcua
