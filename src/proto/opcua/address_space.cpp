#include "proto/opcua/address_space.hpp"

#include "proto/ads/index_group.hpp"
#include "proto/opcua/node_ids.hpp"

namespace virtcom::proto::opcua {

namespace {

// An array of structs is served element by element up to this many (beyond: the first ones).
constexpr uint32_t kMaxStructElements = 1000;


Node object(NodeId id, uint16_t ns, std::string name, uint32_t typeDefinition) {
  Node n;
  n.id = std::move(id);
  n.browseName = QualifiedName{ns, name};
  n.displayName = std::move(name);
  n.typeDefinition = typeDefinition;
  return n;
}

Node fixedVariable(uint32_t id, std::string name, Variant value, uint32_t dataType, int32_t valueRank, uint32_t typeDefinition) {
  Node n = object(NodeId::num(0, id), 0, std::move(name), typeDefinition);
  n.nodeClass = NodeClass::Variable;
  n.fixed = std::move(value);
  n.dataType = NodeId::num(0, dataType);
  n.valueRank = valueRank;
  return n;
}

Variant stringArray(const std::vector<std::string>& items) {
  Variant v{BuiltinType::String, true, {}, {}};
  for (const auto& s : items) v.values.emplace_back(String{s, false});
  return v;
}

}  // namespace

bool isReferenceSubtype(uint32_t type, uint32_t base, bool includeSubtypes) {
  if (type == base) return true;
  if (!includeSubtypes) return false;
  // The reference type tree the server's references use (OPC 10000-5 §11).
  auto parent = [](uint32_t t) -> uint32_t {
    switch (t) {
      case ids::kHierarchicalReferences:
      case ids::kNonHierarchicalReferences: return ids::kReferences;
      case ids::kHasChild:
      case ids::kOrganizes: return ids::kHierarchicalReferences;
      case ids::kAggregates:
      case ids::kHasSubtype: return ids::kHasChild;
      case ids::kHasComponent:
      case ids::kHasProperty: return ids::kAggregates;
      case ids::kHasTypeDefinition: return ids::kNonHierarchicalReferences;
      default: return 0;
    }
  };
  for (uint32_t t = parent(type); t != 0; t = parent(t))
    if (t == base) return true;
  return false;
}

AddressSpace::AddressSpace(const ads::SymbolTable& table, const AddressSpaceConfig& config)
    : table_(table), config_(config) {
  namespaces_ = {"http://opcfoundation.org/UA/", config_.applicationUri, "http://PLCopen.org/OpcUa/IEC61131-3/",
                 "http://opcfoundation.org/UA/DI/", "urn:virtcom:Application"};
  addStandardNodes();
  for (const ads::Symbol& s : table_.symbols()) {
    auto dot = s.name.find('.');
    std::string_view pou = dot == std::string::npos ? std::string_view("Globals") : std::string_view(s.name).substr(0, dot);
    std::string_view name = dot == std::string::npos ? std::string_view(s.name) : std::string_view(s.name).substr(dot + 1);
    uint32_t offset = s.indexOffset;
    const ads::MemoryLayout& l = table_.layout();
    const ads::ByteRange* area = nullptr;
    switch (static_cast<ads::IndexGroup>(s.indexGroup)) {
      case ads::IndexGroup::InputBits: area = &l.inputs; break;
      case ads::IndexGroup::OutputBits: area = &l.outputs; break;
      case ads::IndexGroup::MemoryBits: area = &l.memory; break;
      default: break;
    }
    const uint32_t parent = folderFor(pou);
    if (area) {
      // A single located bit: a Boolean at byte area + io / 8, bit io % 8.
      Node n = object(NodeId::str(ids::kPlcNamespace, plcNodeName(s.name)), ids::kPlcNamespace, std::string(name), ids::kBaseDataVariableType);
      n.nodeClass = NodeClass::Variable;
      n.source = ValueSource::Plc;
      n.plc = PlcValue{BuiltinType::Boolean, area->offset + offset / 8, 1, 1, static_cast<int8_t>(offset % 8), false, false, {}};
      n.dataType = NodeId::num(0, static_cast<uint32_t>(BuiltinType::Boolean));
      n.writable = !(s.flags & ads::kSymbolFlagReadOnly) && !table_.touchesReadOnly(n.plc.offset, 1);
      link(parent, ids::kHasComponent, add(std::move(n)));
      continue;
    }
    addPlcVariable(parent, s.name, name, s.type, offset, &s);
  }
  addDevices();
}

void AddressSpace::addDevices() {
  if (config_.devices.empty()) return;
  const std::string prefix = "|dev|" + config_.applicationName;
  const uint32_t folder = add(object(NodeId::str(ids::kPlcNamespace, prefix), ids::kPlcNamespace, "Devices", ids::kFolderType));
  link(*find(NodeId::num(0, ids::kObjectsFolder)), ids::kOrganizes, folder);
  const uint32_t extraStart = table_.layout().dataSize;
  for (const ExtraObject& device : config_.devices) {
    const std::string path = prefix + "." + device.name;
    const uint32_t index = add(object(NodeId::str(ids::kPlcNamespace, path), ids::kPlcNamespace, device.name, ids::kBaseObjectType));
    link(folder, ids::kOrganizes, index);
    for (const ExtraVariable& v : device.variables) {
      Node n = object(NodeId::str(ids::kPlcNamespace, path + "." + v.name), ids::kPlcNamespace, v.name, ids::kBaseDataVariableType);
      n.nodeClass = NodeClass::Variable;
      n.source = ValueSource::Plc;
      n.plc = PlcValue{v.type, extraStart + v.offset, v.size, 1, -1, false, false, {}};
      n.dataType = NodeId::num(0, static_cast<uint32_t>(v.type));
      n.writable = false;  // the simulation's state: what the devices do, not an input
      link(index, ids::kHasComponent, add(std::move(n)));
    }
  }
}

std::string AddressSpace::plcNodeName(std::string_view path) const {
  return "|var|" + config_.applicationName + ".Application." + std::string(path);
}

uint32_t AddressSpace::add(Node n) {
  const auto index = static_cast<uint32_t>(nodes_.size());
  if (n.id.kind == NodeId::Kind::Numeric && n.id.ns == 0) numeric_[n.id.numeric] = index;
  else if (n.id.kind == NodeId::Kind::String && n.id.ns == ids::kPlcNamespace) named_[n.id.text] = index;
  nodes_.push_back(std::move(n));
  return index;
}

void AddressSpace::link(uint32_t from, uint32_t type, uint32_t to) {
  nodes_[from].references.push_back({type, to, true});
  nodes_[to].references.push_back({type, from, false});
}

std::optional<uint32_t> AddressSpace::find(const NodeId& id) const {
  if (id.kind == NodeId::Kind::Numeric && id.ns == 0) {
    auto it = numeric_.find(id.numeric);
    if (it != numeric_.end()) return it->second;
  } else if (id.kind == NodeId::Kind::String && id.ns == ids::kPlcNamespace) {
    auto it = named_.find(id.text);
    if (it != named_.end()) return it->second;
  }
  return std::nullopt;
}

void AddressSpace::addStandardNodes() {
  const uint32_t root = add(object(NodeId::num(0, ids::kRootFolder), 0, "Root", ids::kFolderType));
  const uint32_t objects = add(object(NodeId::num(0, ids::kObjectsFolder), 0, "Objects", ids::kFolderType));
  const uint32_t types = add(object(NodeId::num(0, ids::kTypesFolder), 0, "Types", ids::kFolderType));
  const uint32_t views = add(object(NodeId::num(0, ids::kViewsFolder), 0, "Views", ids::kFolderType));
  for (uint32_t child : {objects, types, views}) link(root, ids::kOrganizes, child);
  const uint32_t server = add(object(NodeId::num(0, ids::kServer), 0, "Server", ids::kServerType));
  link(objects, ids::kOrganizes, server);
  link(server, ids::kHasProperty, add(fixedVariable(ids::kServerArray, "ServerArray", stringArray({config_.applicationUri}),
                                                    static_cast<uint32_t>(BuiltinType::String), 1, ids::kPropertyType)));
  // The namespace table is complete only once the constructor set it: filled in here by value.
  link(server, ids::kHasProperty, add(fixedVariable(ids::kNamespaceArray, "NamespaceArray", stringArray(namespaces_),
                                                    static_cast<uint32_t>(BuiltinType::String), 1, ids::kPropertyType)));
  Node status = fixedVariable(ids::kServerStatus, "ServerStatus", {}, ids::kServerStatusDataType, -1, ids::kServerStatusType);
  status.source = ValueSource::ServerStatus;
  const uint32_t statusIndex = add(std::move(status));
  link(server, ids::kHasComponent, statusIndex);
  struct Part {
    uint32_t id;
    const char* name;
    ValueSource source;
    uint32_t dataType;
  };
  for (const Part& p : {Part{ids::kServerStatusStartTime, "StartTime", ValueSource::StartTime, ids::kUtcTime},
                        Part{ids::kServerStatusCurrentTime, "CurrentTime", ValueSource::CurrentTime, ids::kUtcTime},
                        Part{ids::kServerStatusState, "State", ValueSource::ServerState, ids::kServerState}}) {
    Node n = fixedVariable(p.id, p.name, {}, p.dataType, -1, ids::kBaseDataVariableType);
    n.source = p.source;
    link(statusIndex, ids::kHasComponent, add(std::move(n)));
  }
}

uint32_t AddressSpace::folderFor(std::string_view pou) {
  auto key = std::string(pou);
  auto it = folders_.find(key);
  if (it != folders_.end()) return it->second;
  Node n = object(NodeId::str(ids::kPlcNamespace, plcNodeName(pou)), ids::kPlcNamespace, key, ids::kFolderType);
  const uint32_t index = add(std::move(n));
  link(*find(NodeId::num(0, ids::kObjectsFolder)), ids::kOrganizes, index);
  folders_.emplace(key, index);
  return index;
}

void AddressSpace::addPlcVariable(uint32_t parent, const std::string& path, std::string_view name, const std::string& type,
                                  uint32_t offset, const ads::Symbol* symbol) {
  const ads::DataType* t = table_.findType(type);
  const bool symbolReadOnly = symbol && (symbol->flags & ads::kSymbolFlagReadOnly);
  NodeId id = NodeId::str(ids::kPlcNamespace, plcNodeName(path));
  if (t && !t->members.empty()) {
    // A struct: an object whose components are its members.
    const uint32_t index = add(object(std::move(id), ids::kPlcNamespace, std::string(name), ids::kBaseObjectType));
    link(parent, ids::kHasComponent, index);
    for (const auto& m : t->members) addPlcVariable(index, path + "." + m.name, m.name, m.type, offset + m.offset, nullptr);
    return;
  }
  PlcValue v;
  v.offset = offset;
  uint32_t size = t ? t->size : symbol ? symbol->size : 0;
  uint32_t adsType = t ? t->adsType : symbol ? symbol->adsType : ads::adst::kVoid;
  if (t && !t->dims.empty()) {
    const ads::DataType* element = table_.findType(t->baseType);
    if (!element) return;
    uint32_t count = 1;
    for (const auto& d : t->dims) count *= d.elementCount;
    if (!element->members.empty() || !element->dims.empty()) {
      // An array of structs (or of arrays): an object with one component per element.
      const uint32_t index = add(object(std::move(id), ids::kPlcNamespace, std::string(name), ids::kBaseObjectType));
      link(parent, ids::kHasComponent, index);
      const int32_t lo = t->dims[0].lowerBound;
      for (uint32_t i = 0; i < std::min(count, kMaxStructElements) && t->dims.size() == 1; ++i) {
        std::string elementName = std::string(name) + "[" + std::to_string(lo + static_cast<int32_t>(i)) + "]";
        std::string elementPath = path + "[" + std::to_string(lo + static_cast<int32_t>(i)) + "]";
        addPlcVariable(index, elementPath, elementName, t->baseType, offset + i * element->size, nullptr);
      }
      return;
    }
    v.isArray = true;
    v.count = count;
    for (const auto& d : t->dims) v.dims.push_back(d.elementCount);
    size = element->size;
    adsType = element->adsType;
  }
  v.type = builtinOf(adsType);
  if (v.type == BuiltinType::Null) return;  // pointers, references, interfaces: not served
  v.elementSize = size;
  v.wide = adsType == ads::adst::kWstring;
  Node n = object(std::move(id), ids::kPlcNamespace, std::string(name), ids::kBaseDataVariableType);
  n.nodeClass = NodeClass::Variable;
  n.source = ValueSource::Plc;
  n.dataType = NodeId::num(0, static_cast<uint32_t>(v.type));
  n.valueRank = v.isArray ? static_cast<int32_t>(v.dims.size()) : -1;
  n.writable = !symbolReadOnly && !table_.touchesReadOnly(offset, v.elementSize * v.count);
  n.plc = std::move(v);
  link(parent, ids::kHasComponent, add(std::move(n)));
}

BuiltinType builtinOf(uint32_t adsType) {
  namespace adst = ads::adst;
  switch (adsType) {
    case adst::kBit: return BuiltinType::Boolean;
    case adst::kInt8: return BuiltinType::SByte;
    case adst::kUint8: return BuiltinType::Byte;
    case adst::kInt16: return BuiltinType::Int16;
    case adst::kUint16: return BuiltinType::UInt16;
    case adst::kInt32: return BuiltinType::Int32;
    case adst::kUint32: return BuiltinType::UInt32;
    case adst::kInt64: return BuiltinType::Int64;
    case adst::kUint64: return BuiltinType::UInt64;
    case adst::kReal32: return BuiltinType::Float;
    case adst::kReal64: return BuiltinType::Double;
    case adst::kString:
    case adst::kWstring: return BuiltinType::String;
    default: return BuiltinType::Null;
  }
}

}  // namespace virtcom::proto::opcua
