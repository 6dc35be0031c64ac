#pragma once
// The services of services.def: one handler each, dispatched by the request's encoding id.
// A handler reads the request body (after the RequestHeader) and appends the response body
// (after the ResponseHeader); it returns 0 or the Bad status of a ServiceFault, in which case
// what it appended is discarded.
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>

#include "proto/opcua/binary_codec.hpp"
#include "proto/opcua/server_core.hpp"

namespace virtcom::proto::opcua {

inline constexpr uint32_t kServiceFaultId = 397;
// The secure channel's own messages (OPC 10000-6 §6.7.4, encoding ids of Annex A), outside the
// service table: OpenSecureChannel issues or renews the channel's token (security mode None: 1).
inline constexpr uint32_t kOpenSecureChannelRequestId = 446, kOpenSecureChannelResponseId = 449, kCloseSecureChannelRequestId = 452;
inline constexpr uint32_t kSecureChannelIssue = 0, kSecureChannelRenew = 1, kSecurityModeNone = 1;
inline constexpr const char* kSecurityPolicyNone = "http://opcfoundation.org/UA/SecurityPolicy#None";
inline constexpr const char* kTransportProfileBinary = "http://opcfoundation.org/UA-Profile/Transport/uatcp-uasc-uabinary";

// Attribute ids (OPC 10000-6 Annex A.1): what Read, Write and monitored items name.
enum Attribute : uint32_t {
  kNodeIdAttr = 1, kNodeClassAttr = 2, kBrowseNameAttr = 3, kDisplayNameAttr = 4, kDescriptionAttr = 5,
  kWriteMaskAttr = 6, kUserWriteMaskAttr = 7, kEventNotifierAttr = 12, kValueAttr = 13, kDataTypeAttr = 14,
  kValueRankAttr = 15, kArrayDimensionsAttr = 16, kAccessLevelAttr = 17, kUserAccessLevelAttr = 18,
  kMinimumSamplingIntervalAttr = 19, kHistorizingAttr = 20,
};

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
  uint32_t requestId = 0, requestHandle = 0;
  SecurityMode securityMode = SecurityMode::None;  // of the channel
  std::span<const uint8_t> clientCertificate{};    // the channel's client certificate (DER), with a mode other than None
};

// What a handler returns when it answers later (Publish): no response now.
inline constexpr uint32_t kDeferredResponse = 0x00000001;

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
void encodeEndpointDescription(Writer& w, const ServerCore& core, SecurityMode mode);
// The EndpointDescriptions array: one per mode of --opcua-security.
void encodeEndpointDescriptions(Writer& w, const ServerCore& core);
// The Value attribute of a variable as a Variant (0), or a Bad status (nothing appended).
uint32_t encodeValueAttribute(Writer& w, const ServerCore& core, const Node& n);

// Channel side of subscriptions: samples due items and answers queued Publish requests of
// `session` (each answer is appended to `body` and handed to `send` with its request id).
void runSubscriptions(ServerCore& core, Session& session, int64_t nowNs, std::vector<uint8_t>& body,
                      const std::function<void(uint32_t requestId)>& send);
// The earliest time a subscription of `session` needs the channel to run again.
int64_t nextSubscriptionDueNs(const Session& session);

// Reads past structures nothing here uses (the server: a client's; the client: a server's):
// an ApplicationDescription, a String array, a SignatureData (Algorithm, Signature).
bool skipApplicationDescription(Reader& in);
bool skipStringArray(Reader& in);
bool skipSignature(Reader& in);

// An empty DiagnosticInfo array (every response's last field).
inline void encodeNoDiagnostics(Writer& w) { w.i32(0); }

}  // namespace virtcom::proto::opcua
