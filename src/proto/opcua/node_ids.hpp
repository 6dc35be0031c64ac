#pragma once
// The standard (namespace 0) node ids the server uses (docs/opcua.md, Wire reference: Standard
// nodes; OPC 10000-6 Annex A, NodeIds.csv of the specification) and the namespace of the PLC's
// variables.
#include <cstdint>

namespace virtcom::proto::opcua::ids {

// Folders and the Server object.
inline constexpr uint32_t kRootFolder = 84, kObjectsFolder = 85, kTypesFolder = 86, kViewsFolder = 87;
inline constexpr uint32_t kServer = 2253, kServerArray = 2254, kNamespaceArray = 2255, kServerStatus = 2256,
                          kServerStatusStartTime = 2257, kServerStatusCurrentTime = 2258, kServerStatusState = 2259;
// Reference types.
inline constexpr uint32_t kReferences = 31, kNonHierarchicalReferences = 32, kHierarchicalReferences = 33,
                          kHasChild = 34, kOrganizes = 35, kHasTypeDefinition = 40, kAggregates = 44,
                          kHasSubtype = 45, kHasProperty = 46, kHasComponent = 47;
// Type definitions.
inline constexpr uint32_t kBaseObjectType = 58, kFolderType = 61, kBaseDataVariableType = 63, kPropertyType = 68,
                          kServerType = 2004, kServerStatusType = 2138;
// Data types beyond the built-ins (whose DataType node id is their type id).
inline constexpr uint32_t kBaseDataType = 24, kServerState = 852, kServerStatusDataType = 862,
                          kServerStatusDataTypeBinary = 864, kUtcTime = 294;
// Identity tokens (their binary encoding ids, as an ActivateSession's ExtensionObject names them).
inline constexpr uint32_t kAnonymousIdentityToken = 321, kUserNameIdentityToken = 324;

// Namespace 4 holds the PLC's variables, as in CODESYS (docs/opcua.md, Node ids).
inline constexpr uint16_t kPlcNamespace = 4;

}  // namespace virtcom::proto::opcua::ids
