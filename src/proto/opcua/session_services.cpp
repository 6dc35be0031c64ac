// The services a client calls before and around its session (docs/opcua.md, Services):
// FindServers, GetEndpoints, CreateSession, ActivateSession, CloseSession; and the service table.
#include <algorithm>
#include <random>

#include "proto/opcua/identity.hpp"
#include "proto/opcua/services.hpp"

namespace virtcom::proto::opcua {

namespace {

constexpr ServiceEntry kServices[] = {
#define X(name, request, response, access) {#name, request, response, ServiceAccess::access, handle##name},
#include "proto/opcua/services.def"
#undef X
};

constexpr uint32_t kApplicationTypeServer = 0;
// Session timeouts the server grants (ms): clients ask for anything; 0 means "the server's choice".
constexpr double kMinSessionTimeoutMs = 10'000, kMaxSessionTimeoutMs = 3'600'000, kDefaultSessionTimeoutMs = 60'000;
constexpr size_t kNonceBytes = 32;

void encodeNonce(Writer& w) {
  thread_local std::mt19937 random{std::random_device{}()};
  w.i32(static_cast<int32_t>(kNonceBytes));
  for (size_t i = 0; i < kNonceBytes; ++i) w.u8(static_cast<uint8_t>(random()));
}

void encodeNullSignature(Writer& w) {
  w.nullString();
  w.nullString();
}

constexpr uint32_t kDecodingError = static_cast<uint32_t>(StatusCodeValue::BadDecodingError);

}  // namespace

bool skipApplicationDescription(Reader& in) {
  std::string text;
  LocalizedText name;
  uint32_t type = 0, urls = 0;
  if (!decode(in, text) || !decode(in, text) || !decode(in, name) || !in.u32(type) || !decode(in, text) ||
      !decode(in, text) || !in.arrayLength(urls, 4))
    return false;
  for (uint32_t i = 0; i < urls; ++i)
    if (!decode(in, text)) return false;
  return true;
}

bool skipStringArray(Reader& in) {
  uint32_t n = 0;
  if (!in.arrayLength(n, 4)) return false;
  std::string s;
  for (uint32_t i = 0; i < n; ++i)
    if (!decode(in, s)) return false;
  return true;
}

// SignatureData: Algorithm (String), Signature (ByteString).
bool skipSignature(Reader& in) {
  std::string s;
  return decode(in, s) && decode(in, s);
}

const ServiceEntry* findService(uint32_t requestId) {
  for (const ServiceEntry& e : kServices)
    if (e.requestId == requestId) return &e;
  return nullptr;
}

std::span<const ServiceEntry> allServices() { return kServices; }

bool decode(Reader& r, RequestHeader& h) {
  return decode(r, h.authenticationToken) && decode(r, h.timestamp) && r.u32(h.requestHandle) &&
         r.u32(h.returnDiagnostics) && decode(r, h.auditEntryId) && r.u32(h.timeoutHint) && decode(r, h.additionalHeader);
}

void encodeApplicationDescription(Writer& w, const ServerCore& core) {
  w.string(core.config().names.applicationUri);
  w.string("urn:virtcom");
  encode(w, LocalizedText{"en", core.config().names.applicationName + " soft PLC"});
  w.u32(kApplicationTypeServer);
  w.nullString();  // GatewayServerUri
  w.nullString();  // DiscoveryProfileUri
  w.i32(1);
  w.string(core.endpointUrl());
}

void encodeEndpointDescription(Writer& w, const ServerCore& core) {
  w.string(core.endpointUrl());
  encodeApplicationDescription(w, core);
  w.nullString();  // ServerCertificate: none with policy None
  w.u32(kSecurityModeNone);
  w.string(kSecurityPolicyNone);
  encodeUserTokenPolicies(w, core.config());
  w.string(kTransportProfileBinary);
  w.u8(0);  // SecurityLevel: the lowest (no security)
}

uint32_t handleFindServers(ServiceContext& ctx, Reader& in, Writer& out) {
  std::string url;
  if (!decode(in, url) || !skipStringArray(in) || !skipStringArray(in)) return kDecodingError;
  out.i32(1);
  encodeApplicationDescription(out, ctx.core);
  return 0;
}

uint32_t handleGetEndpoints(ServiceContext& ctx, Reader& in, Writer& out) {
  std::string url;
  uint32_t profiles = 0;
  if (!decode(in, url) || !skipStringArray(in) || !in.arrayLength(profiles, 4)) return kDecodingError;
  // A client asking only for profiles other than UA TCP binary gets no endpoint.
  bool binary = profiles == 0;
  for (uint32_t i = 0; i < profiles; ++i) {
    std::string profile;
    if (!decode(in, profile)) return kDecodingError;
    binary = binary || profile == kTransportProfileBinary;
  }
  out.i32(binary ? 1 : 0);
  if (binary) encodeEndpointDescription(out, ctx.core);
  return 0;
}

uint32_t handleCreateSession(ServiceContext& ctx, Reader& in, Writer& out) {
  std::string serverUri, endpointUrl, sessionName;
  ByteString clientNonce, clientCertificate;
  double timeoutMs = 0;
  uint32_t maxResponse = 0;
  if (!skipApplicationDescription(in) || !decode(in, serverUri) || !decode(in, endpointUrl) || !decode(in, sessionName) ||
      !decode(in, clientNonce) || !decode(in, clientCertificate) || !decode(in, timeoutMs) || !in.u32(maxResponse))
    return kDecodingError;
  timeoutMs = timeoutMs > 0 ? std::clamp(timeoutMs, kMinSessionTimeoutMs, kMaxSessionTimeoutMs) : kDefaultSessionTimeoutMs;
  Session* s = ctx.core.createSession(ctx.channelId, timeoutMs, sessionName, ctx.nowNs);
  if (!s) return static_cast<uint32_t>(StatusCodeValue::BadTooManySessions);
  encode(out, NodeId::num(1, s->id));
  encode(out, NodeId::num(1, s->token));
  encode(out, s->timeoutMs);
  encodeNonce(out);
  out.nullString();  // ServerCertificate
  out.i32(1);
  encodeEndpointDescription(out, ctx.core);
  out.i32(0);  // ServerSoftwareCertificates
  encodeNullSignature(out);
  out.u32(ctx.core.config().maxMessageBytes);
  return 0;
}

uint32_t handleActivateSession(ServiceContext& ctx, Reader& in, Writer& out) {
  uint32_t certificates = 0;
  if (!skipSignature(in) || !in.arrayLength(certificates, 8)) return kDecodingError;
  for (uint32_t i = 0; i < certificates; ++i)
    if (!skipSignature(in)) return kDecodingError;  // SignedSoftwareCertificate: two ByteStrings
  ExtensionObject identity;
  if (!skipStringArray(in) || !decode(in, identity) || !skipSignature(in)) return kDecodingError;
  UserAccess access = UserAccess::None;
  if (const uint32_t status = checkIdentity(ctx.core.config(), identity, access); status != 0) return status;
  ctx.session->activated = true;
  ctx.session->access = access;
  ctx.session->channelId = ctx.channelId;
  encodeNonce(out);
  out.i32(0);  // Results
  encodeNoDiagnostics(out);
  return 0;
}

uint32_t handleCloseSession(ServiceContext& ctx, Reader& in, Writer&) {
  bool deleteSubscriptions = false;
  if (!decode(in, deleteSubscriptions)) return kDecodingError;
  ctx.core.closeSession(ctx.session->id);
  ctx.session = nullptr;
  return 0;
}

}  // namespace virtcom::proto::opcua
