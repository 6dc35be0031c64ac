#pragma once
// The services of services.def: one handler each, dispatched by the request's encoding id.
// A handler reads the request body (after the RequestHeader) and appends the response body
// (after the ResponseHeader); it returns 0 or the Bad status of a ServiceFault, in which case
// what it appended is discarded.
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "proto/opcua/binary_codec.hpp"
#include "proto/opcua/server_core.hpp"

namespace virtcom::proto::opcua {

inline constexpr uint32_t kServiceFaultId = 397;
inline constexpr const char* kSecurityPolicyNone = "http://opcfoundation.org/UA/SecurityPolicy#None";
inline constexpr const char* kTransportProfileBinary = "http://opcfoundation.org/UA-Profile/Transport/uatcp-uasc-uabinary";

enum class ServiceAccess : uint8_t { Channel, Session, Active };

struct RequestHeader {
  NodeId authenticationToken;
  DateTime timestamp;
  uint32_t requestHandle = 0, returnDiagnostics = 0, timeoutHint = 0;
  std::string auditEntryId;
  ExtensionObject additionalHeader;
};
bool decode(Reader& r, RequestHeader& h);

// What a handler works with: the shared server state and the request's channel and session.
struct ServiceContext {
  ServerCore& core;
  uint32_t channelId = 0;
  Session* session = nullptr;  // set for Session and Active services
  int64_t nowNs = 0;
};

using ServiceHandler = uint32_t (*)(ServiceContext&, Reader&, Writer&);

struct ServiceEntry {
  const char* name;
  uint32_t requestId, responseId;
  ServiceAccess access;
  ServiceHandler handler;
};
// The entry of a request encoding id, or nullptr.
const ServiceEntry* findService(uint32_t requestId);
// Every entry of services.def, in its order.
std::span<const ServiceEntry> allServices();

#define X(name, request, response, access) uint32_t handle##name(ServiceContext& ctx, Reader& in, Writer& out);
#include "proto/opcua/services.def"
#undef X

// Shared by the handlers: the ApplicationDescription and EndpointDescription of this server.
void encodeApplicationDescription(Writer& w, const ServerCore& core);
void encodeEndpointDescription(Writer& w, const ServerCore& core);
// An empty DiagnosticInfo array (every response's last field).
inline void encodeNoDiagnostics(Writer& w) { w.i32(0); }

}  // namespace virtcom::proto::opcua
