// The services a client calls before and around its session (docs/opcua.md, Services):
// FindServers, GetEndpoints, CreateSession, ActivateSession, CloseSession; and the service table.
#include <algorithm>
#include <random>

#include "proto/opcua/crypto.hpp"
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
constexpr const char* kRsaSha256Signature = "http://www.w3.org/2001/04/xmldsig-more#rsa-sha256";

// A new session nonce, kept in the session (the client signs it with the server certificate,
// and an encrypted password ends with it), and written out. From the crypto module where
// security is on; else not loading libcrypto for it.
bool encodeNonce(Writer& w, const ServerCore& core, Session& s) {
  if (core.config().pki) {
    if (!crypto().randomBytes(s.nonce.data(), s.nonce.size())) return false;
  } else {
    thread_local std::mt19937 random{std::random_device{}()};
    for (uint8_t& b : s.nonce) b = static_cast<uint8_t>(random());
  }
  w.byteString(s.nonce);
  return true;
}

void encodeNullSignature(Writer& w) {
  w.nullString();
  w.nullString();
}

// SignatureData (OPC 10000-4 §7.36) of the server over the client's certificate and nonce.
bool encodeServerSignature(Writer& w, const Pki& pki, std::span<const uint8_t> clientCertificate, const ByteString& clientNonce) {
  std::vector<uint8_t> data(clientCertificate.begin(), clientCertificate.end());
  data.insert(data.end(), clientNonce.bytes.begin(), clientNonce.bytes.end());
  std::vector<uint8_t> signature(rsaKeyBytes(pki.certificate));
  size_t length = 0;
  if (!crypto().rsaSha256Sign(pki.keyPem.data(), pki.keyPem.size(), data.data(), data.size(), signature.data(), signature.size(), &length))
    return false;
  w.string(kRsaSha256Signature);
  w.byteString(std::span(signature).first(length));
  return true;
}

// The client's SignatureData over the server's certificate and the session's last nonce, checked
// with the channel's client certificate.
bool clientSignatureValid(const ServiceContext& ctx, const std::string& algorithm, const ByteString& signature) {
  const Pki& pki = *ctx.core.config().pki;
  std::vector<uint8_t> data(pki.certificate.begin(), pki.certificate.end());
  data.insert(data.end(), ctx.session->nonce.begin(), ctx.session->nonce.end());
  return algorithm == kRsaSha256Signature &&
         crypto().rsaSha256Verify(ctx.clientCertificate.data(), ctx.clientCertificate.size(), data.data(), data.size(),
                                  signature.view().data(), signature.bytes.size());
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

void encodeEndpointDescription(Writer& w, const ServerCore& core, SecurityMode mode) {
  w.string(core.endpointUrl());
  encodeApplicationDescription(w, core);
  if (const Pki* pki = core.config().pki.get()) w.byteString(pki->certificate);
  else w.nullString();  // ServerCertificate: none without a PKI folder
  w.u32(static_cast<uint32_t>(mode));
  w.string(mode == SecurityMode::None ? kSecurityPolicyNone : kSecurityPolicyBasic256Sha256);
  encodeUserTokenPolicies(w, core.config());
  w.string(kTransportProfileBinary);
  // SecurityLevel: relative, the higher the more secure; 0 for None.
  w.u8(static_cast<uint8_t>(static_cast<uint32_t>(mode) - 1));
}

void encodeEndpointDescriptions(Writer& w, const ServerCore& core) {
  w.i32(static_cast<int32_t>(core.config().securityModes.size()));
  for (SecurityMode mode : core.config().securityModes) encodeEndpointDescription(w, core, mode);
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
  if (binary) encodeEndpointDescriptions(out, ctx.core);
  else out.i32(0);
  return 0;
}

uint32_t handleCreateSession(ServiceContext& ctx, Reader& in, Writer& out) {
  std::string serverUri, endpointUrl, sessionName;
  ByteString clientNonce, clientCertificate;
  double timeoutMs = 0;
  uint32_t maxResponse = 0;
  std::string clientUri;
  if (Reader uri = in; !decode(uri, clientUri)) return kDecodingError;  // the ApplicationDescription's first field
  if (!skipApplicationDescription(in) || !decode(in, serverUri) || !decode(in, endpointUrl) || !decode(in, sessionName) ||
      !decode(in, clientNonce) || !decode(in, clientCertificate) || !decode(in, timeoutMs) || !in.u32(maxResponse))
    return kDecodingError;
  // A channel of a mode no endpoint offers (None, kept open for discovery) carries no session.
  if (!ctx.core.offers(ctx.securityMode)) return static_cast<uint32_t>(StatusCodeValue::BadSecurityModeRejected);
  const bool secured = ctx.securityMode != SecurityMode::None;
  // OPC 10000-4 §5.6.2: the nonce of a secured session has 32 bytes at least, and the client
  // certificate is the channel's and names the client's ApplicationUri.
  if (secured && clientNonce.bytes.size() < kSecureNonceBytes) return static_cast<uint32_t>(StatusCodeValue::BadNonceInvalid);
  if (secured && !std::ranges::equal(clientCertificate.view(), ctx.clientCertificate))
    return static_cast<uint32_t>(StatusCodeValue::BadSecurityChecksFailed);
  if (secured && certificateUri(ctx.clientCertificate) != clientUri)
    return static_cast<uint32_t>(StatusCodeValue::BadCertificateUriInvalid);
  timeoutMs = timeoutMs > 0 ? std::clamp(timeoutMs, kMinSessionTimeoutMs, kMaxSessionTimeoutMs) : kDefaultSessionTimeoutMs;
  Session* s = ctx.core.createSession(ctx.channelId, timeoutMs, sessionName, ctx.nowNs);
  if (!s) return static_cast<uint32_t>(StatusCodeValue::BadTooManySessions);
  s->securityMode = ctx.securityMode;
  s->clientCertificate.assign(ctx.clientCertificate.begin(), ctx.clientCertificate.end());
  encode(out, NodeId::num(1, s->id));
  encode(out, NodeId::num(1, s->token));
  encode(out, s->timeoutMs);
  if (!encodeNonce(out, ctx.core, *s)) return static_cast<uint32_t>(StatusCodeValue::BadInternalError);
  if (const Pki* pki = ctx.core.config().pki.get()) out.byteString(pki->certificate);
  else out.nullString();  // ServerCertificate
  encodeEndpointDescriptions(out, ctx.core);
  out.i32(0);  // ServerSoftwareCertificates
  if (!secured) encodeNullSignature(out);
  else if (!encodeServerSignature(out, *ctx.core.config().pki, ctx.clientCertificate, clientNonce))
    return static_cast<uint32_t>(StatusCodeValue::BadInternalError);
  out.u32(ctx.core.config().maxMessageBytes);
  return 0;
}

uint32_t handleActivateSession(ServiceContext& ctx, Reader& in, Writer& out) {
  uint32_t certificates = 0;
  std::string algorithm;
  ByteString signature;
  if (!decode(in, algorithm) || !decode(in, signature) || !in.arrayLength(certificates, 8)) return kDecodingError;
  // The session is bound to the security it was created with: never activated over less, and
  // over a secured channel only by the client that created it.
  if (ctx.securityMode < ctx.session->securityMode) return static_cast<uint32_t>(StatusCodeValue::BadSecurityModeInsufficient);
  if (ctx.securityMode != SecurityMode::None) {
    if (!std::ranges::equal(ctx.clientCertificate, ctx.session->clientCertificate))
      return static_cast<uint32_t>(StatusCodeValue::BadSecurityChecksFailed);
    if (!clientSignatureValid(ctx, algorithm, signature)) return static_cast<uint32_t>(StatusCodeValue::BadApplicationSignatureInvalid);
  }
  for (uint32_t i = 0; i < certificates; ++i)
    if (!skipSignature(in)) return kDecodingError;  // SignedSoftwareCertificate: two ByteStrings
  ExtensionObject identity;
  if (!skipStringArray(in) || !decode(in, identity) || !skipSignature(in)) return kDecodingError;
  UserAccess access = UserAccess::None;
  const IdentitySecurity security{ctx.session->nonce, ctx.securityMode == SecurityMode::SignAndEncrypt};
  if (const uint32_t status = checkIdentity(ctx.core.config(), identity, access, security); status != 0) return status;
  ctx.session->activated = true;
  ctx.session->access = access;
  ctx.session->channelId = ctx.channelId;
  if (!encodeNonce(out, ctx.core, *ctx.session)) return static_cast<uint32_t>(StatusCodeValue::BadInternalError);
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
