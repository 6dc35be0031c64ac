#include "proto/opcua/client.hpp"

#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <ctime>

#include "core/clock.hpp"
#include "proto/net/tcp_client.hpp"
#include "proto/opcua/client_security.hpp"
#include "proto/opcua/crypto.hpp"
#include "proto/opcua/node_ids.hpp"
#include "proto/opcua/services.hpp"
#include "proto/opcua/transport.hpp"

namespace virtcom::proto::opcua {

namespace {

constexpr uint32_t kGetEndpointsRequestId = 428, kGetEndpointsResponseId = 431, kCreateSessionRequestId = 461, kCreateSessionResponseId = 464, kActivateSessionRequestId = 467,
                   kActivateSessionResponseId = 470, kCloseSessionRequestId = 473, kCloseSessionResponseId = 476;
constexpr uint32_t kApplicationTypeClient = 1;
// The ApplicationUri of the bridge: also the one of the certificate it makes.
constexpr const char* kApplicationUri = "urn:virtcom:bridge";
constexpr uint32_t kTokenAnonymous = 0, kTokenUserName = 1;  // UserTokenType (OPC 10000-4 §7.43)
constexpr uint32_t kRequestedLifetimeMs = 3'600'000;
// How long close() waits for the server to answer CloseSession.
constexpr int64_t kCloseWaitNs = 100'000'000;

// The RequestHeader (OPC 10000-4 §7.32) of every request.
void encodeRequestHeader(Writer& w, const NodeId& token, uint32_t handle, int64_t timeoutNs) {
  encode(w, token);
  encode(w, dateTimeNow());
  w.u32(handle);
  w.u32(0);          // ReturnDiagnostics: none
  w.nullString();    // AuditEntryId
  w.u32(static_cast<uint32_t>(timeoutNs / 1'000'000));  // TimeoutHint (ms)
  encode(w, ExtensionObject{});
}

// The ResponseHeader (OPC 10000-4 §7.33): its ServiceResult, or nullopt if malformed.
std::optional<uint32_t> decodeResponseHeader(Reader& r) {
  DateTime time;
  uint32_t handle = 0, result = 0;
  DiagnosticInfo diagnostics;
  ExtensionObject additional;
  if (!decode(r, time) || !r.u32(handle) || !r.u32(result) || !decode(r, diagnostics) || !skipStringArray(r) ||
      !decode(r, additional))
    return std::nullopt;
  return result;
}

// The identity token of ActivateSession: an ExtensionObject whose binary body is the token (of
// a user: the password and the algorithm it is encrypted with, none for a plain one).
ExtensionObject identityToken(uint32_t typeId, const std::string& policy, const std::string* user = nullptr,
                              std::span<const uint8_t> password = {}, const char* algorithm = nullptr) {
  std::vector<uint8_t> body;
  Writer w(body);
  w.string(policy);
  if (user) {
    w.string(*user);
    w.byteString(password);
    if (algorithm) w.string(algorithm);
    else w.nullString();
  }
  return ExtensionObject{NodeId::num(0, typeId), ExtensionObject::Body::Binary, std::string(body.begin(), body.end())};
}

}  // namespace

Client::Client(ClientConfig config) : config_(std::move(config)) {
  rx_.resize(config_.bufferBytes);
  tx_.reserve(config_.bufferBytes);
}

Client::~Client() { close(); }

ClientError Client::lost(std::string what) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  rxUsed_ = frameSize_ = 0;
  postedId_ = 0;
  parkedDone_ = false;
  return ClientError{true, 0, std::move(what)};
}

void Client::close() {
  if (fd_ < 0) return;
  const int64_t saved = config_.timeoutNs;
  config_.timeoutNs = std::min(saved, kCloseWaitNs);
  if (!authenticationToken_.isNull()) {
    Writer& w = beginRequest(kCloseSessionRequestId);
    encode(w, true);  // DeleteSubscriptions
    (void)call(kCloseSessionResponseId);
  }
  if (fd_ >= 0) {
    // CloseSecureChannel: no response; the server closes the connection.
    body_.clear();
    Writer b(body_);
    encode(b, NodeId::num(0, kCloseSecureChannelRequestId));
    encodeRequestHeader(b, NodeId{}, ++requestHandle_, config_.timeoutNs);
    beginMessage("CLO");
    Writer w(tx_);
    w.u32(++requestId_);
    w.raw(body_);
    w.put32(4, static_cast<uint32_t>(tx_.size()));
    if (mode_ == SecurityMode::None || sealSymmetric(tx_, 0, mode_, clientKeys_))
      (void)net::sendAll(fd_, tx_, monotonicNowNs() + config_.timeoutNs);
  }
  config_.timeoutNs = saved;
  authenticationToken_ = NodeId{};
  (void)lost("closed");
}

std::expected<void, ClientError> Client::connect() {
  close();
  if (config_.security != SecurityMode::None) {
    if (auto ready = openOwnPki(); !ready) return ready;
    if (auto found = discoverServer(); !found) return found;
  }
  mode_ = config_.security;
  if (auto done = openTransport(); !done) return done;
  if (auto done = openChannel(kSecureChannelIssue); !done) return done;
  if (auto done = createSession(); !done) return done;
  if (auto done = activateSession(); !done) {
    authenticationToken_ = NodeId{};
    close();
    return done;
  }
  return {};
}

std::expected<void, ClientError> Client::openTransport() {
  channelId_ = tokenId_ = previousTokenId_ = sequence_ = lastServerSequence_ = 0;
  auto fd = net::connectTcp(config_.server, monotonicNowNs() + config_.timeoutNs);
  if (!fd) return std::unexpected(lost(fd.error()));
  fd_ = *fd;
  return handshake();
}

std::expected<void, ClientError> Client::openOwnPki() {
  if (pki_) return {};
  if (auto calls = loadCrypto(); !calls)
    return std::unexpected(ClientError{true, 0, "security " + securityModeName(config_.security) + " needs " + calls.error()});
  auto pki = openPki(config_.pkiDir, kApplicationUri);
  if (!pki) return std::unexpected(ClientError{true, 0, pki.error()});
  pki->trustAny = config_.trustAnyServer;
  pki_ = std::move(*pki);
  asymmetric_.ownCertificate = pki_->certificate;
  asymmetric_.ownKeyPem = pki_->keyPem;
  return {};
}

std::expected<void, ClientError> Client::discoverServer() {
  mode_ = SecurityMode::None;
  if (auto done = openTransport(); !done) return done;
  if (auto done = openChannel(kSecureChannelIssue); !done) return done;
  Writer& w = beginRequest(kGetEndpointsRequestId);
  w.string(config_.endpointUrl);
  w.i32(0);  // LocaleIds
  w.i32(0);  // ProfileUris: all
  auto r = call(kGetEndpointsResponseId);
  if (!r) return std::unexpected(r.error().linkLost ? r.error() : lost("GetEndpoints refused: " + r.error().text));
  std::vector<EndpointInfo> endpoints;
  if (!decodeEndpoints(*r, endpoints)) return std::unexpected(lost("a malformed GetEndpoints response"));
  // The secured channel gets a connection of its own, as the servers expect of a discovery.
  close();
  auto endpoint = pickEndpoint(endpoints, config_.security, config_.endpointUrl);
  if (!endpoint) return std::unexpected(ClientError{true, 0, endpoint.error()});
  const std::vector<uint8_t>& certificate = (*endpoint)->certificate;
  const PeerCheck check = checkPeerCertificate(*pki_, certificate, ::time(nullptr), "server");
  if (check.trust != PeerTrust::Trusted) return std::unexpected(ClientError{true, 0, check.message});
  asymmetric_.peerCertificate = certificate;
  return {};
}

std::expected<void, ClientError> Client::handshake() {
  tx_.clear();
  Writer w(tx_);
  const size_t start = opcua::beginMessage(w, "HEL");
  w.u32(kProtocolVersion);
  w.u32(config_.bufferBytes);  // ReceiveBufferSize
  w.u32(config_.bufferBytes);  // SendBufferSize
  w.u32(static_cast<uint32_t>(config_.maxResponseBytes));
  w.u32(0);  // MaxChunkCount: no limit
  w.string(config_.endpointUrl);
  finishMessage(w, start);
  const int64_t deadline = monotonicNowNs() + config_.timeoutNs;
  if (auto sent = net::sendAll(fd_, tx_, deadline); !sent) return std::unexpected(lost(sent.error()));
  std::span<const uint8_t> frame;
  if (auto got = receiveMessage(deadline, frame); !got) return got;
  if (messageTypeOf(frame) != MessageType::Acknowledge) return std::unexpected(lost("the server answered HEL with no ACK"));
  Reader r(frame.subspan(kMessageHeaderSize));
  uint32_t version = 0, receive = 0, send = 0;
  if (!r.u32(version) || !r.u32(receive) || !r.u32(send)) return std::unexpected(lost("a malformed ACK"));
  peerReceiveBuffer_ = std::max(receive, kMinBufferSize);
  return {};
}

void Client::beginMessage(const char* type) {
  tx_.clear();
  Writer w(tx_);
  (void)opcua::beginMessage(w, type);
  w.u32(channelId_);
  if (std::strcmp(type, "OPN") != 0) {
    w.u32(tokenId_);
    w.u32(++sequence_);
  }
}

std::expected<void, ClientError> Client::openChannel(uint32_t requestType) {
  body_.clear();
  Writer b(body_);
  encode(b, NodeId::num(0, kOpenSecureChannelRequestId));
  encodeRequestHeader(b, NodeId{}, ++requestHandle_, config_.timeoutNs);
  b.u32(kProtocolVersion);
  b.u32(requestType);
  b.u32(static_cast<uint32_t>(mode_));
  const bool secured = mode_ != SecurityMode::None;
  if (secured && !crypto().randomBytes(channelNonce_.data(), channelNonce_.size()))
    return std::unexpected(lost("the crypto module gave no random bytes for the channel's nonce"));
  if (secured) b.byteString(channelNonce_);
  else b.nullString();  // ClientNonce: none with policy None
  b.u32(kRequestedLifetimeMs);
  beginMessage("OPN");
  Writer w(tx_);
  if (secured) {
    w.string(kSecurityPolicyBasic256Sha256);
    w.byteString(asymmetric_.ownCertificate);
    std::array<uint8_t, 20> thumbprint{};
    crypto().sha1(asymmetric_.peerCertificate.data(), asymmetric_.peerCertificate.size(), thumbprint.data());
    w.byteString(thumbprint);
  } else {
    w.string(kSecurityPolicyNone);
    w.nullString();  // SenderCertificate
    w.nullString();  // ReceiverCertificateThumbprint
  }
  const size_t headerEnd = tx_.size();
  w.u32(++sequence_);
  w.u32(++requestId_);
  w.raw(body_);
  w.put32(4, static_cast<uint32_t>(tx_.size()));
  if (secured && !sealAsymmetric(tx_, 0, headerEnd, asymmetric_))
    return std::unexpected(lost("could not sign or encrypt the OpenSecureChannel request (is the server's certificate RSA?)"));
  const int64_t now = monotonicNowNs();
  ++requests_;
  if (auto sent = net::sendAll(fd_, tx_, now + config_.timeoutNs); !sent) return std::unexpected(lost(sent.error()));
  if (auto done = transact(requestId_, now + config_.timeoutNs); !done) return done;
  Reader r(std::span<const uint8_t>(body_).subspan(bodyStart_));
  NodeId type;
  uint32_t version = 0, channel = 0, token = 0, lifetimeMs = 0;
  DateTime created;
  ByteString serverNonce;
  if (!decode(r, type)) return std::unexpected(lost("a malformed OpenSecureChannel response"));
  auto result = decodeResponseHeader(r);
  if (!result) return std::unexpected(lost("a malformed OpenSecureChannel response"));
  if (type == NodeId::num(0, kServiceFaultId) || isBad(*result))
    return std::unexpected(lost("the server refused to open a secure channel: " + statusName(*result)));
  if (type != NodeId::num(0, kOpenSecureChannelResponseId) || !r.u32(version) || !r.u32(channel) || !r.u32(token) ||
      !decode(r, created) || !r.u32(lifetimeMs) || !decode(r, serverNonce))
    return std::unexpected(lost("a malformed OpenSecureChannel response"));
  if (secured && !deriveChannelKeys(serverNonce))
    return std::unexpected(lost("the server's channel nonce is not 32 bytes (Basic256Sha256)"));
  channelId_ = channel;
  previousTokenId_ = tokenId_;
  tokenId_ = token;
  renewAtNs_ = now + static_cast<int64_t>(lifetimeMs) * 750'000;  // 75 % of the lifetime (OPC 10000-4 §5.5.2)
  return {};
}

bool Client::deriveChannelKeys(const ByteString& serverNonce) {
  if (serverNonce.bytes.size() != kSecureNonceBytes) return false;
  previousServerKeys_ = serverKeys_;
  // OPC 10000-6 §6.7.5: the client's keys from P_SHA256(ServerNonce, ClientNonce), the server's
  // from P_SHA256(ClientNonce, ServerNonce).
  return deriveKeys(serverNonce.view(), channelNonce_, clientKeys_) && deriveKeys(channelNonce_, serverNonce.view(), serverKeys_);
}

std::expected<void, ClientError> Client::createSession() {
  const bool secured = mode_ != SecurityMode::None;
  std::array<uint8_t, kSecureNonceBytes> clientNonce{};
  if (secured && !crypto().randomBytes(clientNonce.data(), clientNonce.size()))
    return std::unexpected(lost("the crypto module gave no random bytes for the session's nonce"));
  Writer& w = beginRequest(kCreateSessionRequestId);
  // Secured, the server checks that the certificate names the ApplicationUri.
  w.string(secured ? certificateUri(asymmetric_.ownCertificate) : kApplicationUri);
  w.string("urn:virtcom");  // ProductUri
  encode(w, LocalizedText{"en", "virtcom bridge"});
  w.u32(kApplicationTypeClient);
  w.nullString();  // GatewayServerUri
  w.nullString();  // DiscoveryProfileUri
  w.i32(0);        // DiscoveryUrls
  w.nullString();  // ServerUri
  w.string(config_.endpointUrl);
  w.string("virtcom bridge");
  if (secured) {
    w.byteString(clientNonce);
    w.byteString(asymmetric_.ownCertificate);
  } else {
    w.nullString();  // ClientNonce
    w.nullString();  // ClientCertificate
  }
  encode(w, config_.sessionTimeoutMs);
  w.u32(static_cast<uint32_t>(config_.maxResponseBytes));
  auto r = call(kCreateSessionResponseId);
  if (!r) return std::unexpected(r.error().linkLost ? r.error() : lost("CreateSession refused: " + r.error().text));
  NodeId sessionId;
  double timeout = 0;
  ByteString nonce, certificate, algorithm, signature;
  std::vector<EndpointInfo> endpoints;
  uint32_t softwareCertificates = 0;
  if (!decode(*r, sessionId) || !decode(*r, authenticationToken_) || !decode(*r, timeout) || !decode(*r, nonce) ||
      !decode(*r, certificate) || !decodeEndpoints(*r, endpoints) || !r->arrayLength(softwareCertificates, 8))
    return std::unexpected(lost("a malformed CreateSession response"));
  for (uint32_t i = 0; i < softwareCertificates; ++i)
    if (!skipSignature(*r)) return std::unexpected(lost("a malformed CreateSession response"));
  if (!decode(*r, algorithm) || !decode(*r, signature)) return std::unexpected(lost("a malformed CreateSession response"));
  // OPC 10000-4 §5.6.2: the server proves it holds the key of the certificate the channel was
  // opened for by signing our certificate and nonce.
  if (secured && (!std::ranges::equal(certificate.view(), asymmetric_.peerCertificate) ||
                  !verifyBoth(asymmetric_.peerCertificate, asymmetric_.ownCertificate, clientNonce, signature.view())))
    return std::unexpected(lost("the server's CreateSession signature is not that of the endpoint's certificate"));
  serverCertificate_.assign(certificate.view().begin(), certificate.view().end());
  sessionNonce_.assign(nonce.view().begin(), nonce.view().end());
  // The policy ids of the identity tokens, from the endpoint of this channel's security (the
  // servers name them as they like: "anonymous", "Anonymous", "0", ...).
  auto endpoint = pickEndpoint(endpoints, mode_, config_.endpointUrl);
  if (!endpoint) return {};
  for (const UserTokenPolicyInfo& t : (*endpoint)->tokens) {
    if (t.tokenType == kTokenAnonymous) anonymousPolicy_ = t.policyId;
    if (t.tokenType != kTokenUserName) continue;
    userNamePolicy_ = t.policyId;
    // An empty SecurityPolicyUri: that of the endpoint (OPC 10000-4 §7.42).
    userNameSecurityPolicy_ = t.securityPolicyUri.empty() ? (*endpoint)->securityPolicyUri : t.securityPolicyUri;
  }
  return {};
}

std::expected<ExtensionObject, ClientError> Client::userNameToken() {
  const std::string& password = config_.password;
  if (userNameSecurityPolicy_ != kSecurityPolicyBasic256Sha256)
    return identityToken(ids::kUserNameIdentityToken, userNamePolicy_, &config_.user, asBytes(password));
  const auto refused = [this](const std::string& why) {
    return std::unexpected(ClientError{false, 0, "cannot send the password of user '" + config_.user + "': " + why});
  };
  if (auto calls = loadCrypto(); !calls) return refused("the server asks for it encrypted, which needs " + calls.error());
  if (serverCertificate_.empty()) return refused("the server asks for it encrypted but sent no certificate in CreateSession");
  const std::vector<uint8_t> secret = encryptPassword(password, sessionNonce_, serverCertificate_);
  if (secret.empty()) return refused("it could not be encrypted with the server's certificate (not RSA?)");
  return identityToken(ids::kUserNameIdentityToken, userNamePolicy_, &config_.user, secret, kRsaOaepUri);
}

std::expected<void, ClientError> Client::activateSession() {
  ExtensionObject identity = identityToken(ids::kAnonymousIdentityToken, anonymousPolicy_);
  if (!config_.user.empty()) {
    auto token = userNameToken();
    if (!token) return std::unexpected(token.error());
    identity = std::move(*token);
  }
  // Secured: our proof that we hold the key of our certificate, the server's certificate and
  // nonce signed (OPC 10000-4 §5.6.3).
  std::vector<uint8_t> signature;
  if (mode_ != SecurityMode::None && (signature = signBoth(asymmetric_.ownKeyPem, asymmetric_.peerCertificate, sessionNonce_)).empty())
    return std::unexpected(lost("could not sign ActivateSession with the client's key"));
  Writer& w = beginRequest(kActivateSessionRequestId);
  if (signature.empty()) {
    w.nullString();  // ClientSignature: Algorithm
    w.nullString();  //                  Signature
  } else {
    w.string(kRsaSha256SignatureUri);
    w.byteString(signature);
  }
  w.i32(0);  // ClientSoftwareCertificates
  w.i32(0);  // LocaleIds
  encode(w, identity);
  w.nullString();  // UserTokenSignature: Algorithm
  w.nullString();  //                     Signature
  auto r = call(kActivateSessionResponseId);
  if (!r) {
    if (r.error().linkLost) return std::unexpected(r.error());
    const std::string who = config_.user.empty() ? "an anonymous session" : "user '" + config_.user + "'";
    return std::unexpected(ClientError{false, r.error().status, "the server refused " + who + ": " + r.error().text});
  }
  return {};
}

Writer& Client::beginRequest(uint32_t requestTypeId) {
  body_.clear();
  Writer w(body_);
  encode(w, NodeId::num(0, requestTypeId));
  encodeRequestHeader(w, authenticationToken_, ++requestHandle_, config_.timeoutNs);
  return request_;
}

std::expected<Reader, ClientError> Client::call(uint32_t responseTypeId) {
  if (fd_ < 0) return std::unexpected(ClientError{true, 0, "not connected"});
  const int64_t now = monotonicNowNs();
  if (channelId_ != 0 && now >= renewAtNs_) {
    std::vector<uint8_t> request;
    request.swap(body_);  // the request waits while the channel's token is renewed (once an hour)
    auto renewed = openChannel(kSecureChannelRenew);
    body_.swap(request);
    if (!renewed) return std::unexpected(renewed.error());
  }
  auto requestId = sendRequest(now + config_.timeoutNs);
  if (!requestId) return std::unexpected(requestId.error());
  if (auto done = transact(*requestId, now + config_.timeoutNs); !done) return std::unexpected(done.error());
  return openResponse(std::span<const uint8_t>(body_).subspan(bodyStart_), responseTypeId);
}

std::expected<uint32_t, ClientError> Client::sendRequest(int64_t deadlineNs) {
  ++requests_;
  // The request as MSG chunks of at most the server's receive buffer.
  const size_t room = symmetricChunkRoom(peerReceiveBuffer_, mode_);
  const uint32_t requestId = ++requestId_;
  tx_.clear();
  std::span<const uint8_t> rest(body_);
  do {
    auto part = rest.first(std::min(room, rest.size()));
    rest = rest.subspan(part.size());
    Writer w(tx_);
    const size_t start = opcua::beginMessage(w, "MSG", rest.empty() ? 'F' : 'C');
    w.u32(channelId_);
    w.u32(tokenId_);
    w.u32(++sequence_);
    w.u32(requestId);
    w.raw(part);
    finishMessage(w, start);
    if (mode_ != SecurityMode::None && !sealSymmetric(tx_, start, mode_, clientKeys_))
      return std::unexpected(lost("could not sign or encrypt a request"));
  } while (!rest.empty());
  if (auto sent = net::sendAll(fd_, tx_, deadlineNs); !sent) return std::unexpected(lost(sent.error()));
  return requestId;
}

std::expected<Reader, ClientError> Client::openResponse(std::span<const uint8_t> body, uint32_t responseTypeId) {
  Reader r(body);
  NodeId type;
  if (!decode(r, type)) return std::unexpected(lost("a malformed response"));
  auto result = decodeResponseHeader(r);
  if (!result) return std::unexpected(lost("a malformed ResponseHeader"));
  if (type == NodeId::num(0, kServiceFaultId) || isBad(*result)) return std::unexpected(ClientError{false, *result, statusName(*result)});
  if (type != NodeId::num(0, responseTypeId))
    return std::unexpected(lost("the response is " + formatNodeId(type) + ", expected i=" + std::to_string(responseTypeId)));
  return r;
}

std::expected<void, ClientError> Client::post() {
  if (fd_ < 0) return std::unexpected(ClientError{true, 0, "not connected"});
  auto requestId = sendRequest(monotonicNowNs() + config_.timeoutNs);
  if (!requestId) return std::unexpected(requestId.error());
  postedId_ = *requestId;
  parkedDone_ = false;
  parked_.clear();
  return {};
}

bool Client::messageWaiting() const {
  if (scanFrame({rx_.data() + frameSize_, rxUsed_ - frameSize_}, config_.maxResponseBytes).status != FrameStatus::NeedMore) return true;
  pollfd p{fd_, POLLIN, 0};
  return ::poll(&p, 1, 0) > 0;
}

std::expected<std::optional<Reader>, ClientError> Client::collect(uint32_t responseTypeId) {
  if (fd_ < 0) return std::unexpected(ClientError{true, 0, "not connected"});
  // What has come is taken; a message that has begun to arrive is waited for (it is on its way).
  while (!parkedDone_ && messageWaiting()) {
    std::span<const uint8_t> frame;
    if (auto got = receiveMessage(monotonicNowNs() + config_.timeoutNs, frame); !got) return std::unexpected(got.error());
    if (auto taken = takeChunk(frame, 0); !taken) return std::unexpected(taken.error());  // 0: no request is awaited
  }
  if (!parkedDone_) return std::nullopt;
  postedId_ = 0;
  parkedDone_ = false;
  auto r = openResponse(parked_, responseTypeId);
  if (!r) return std::unexpected(r.error());
  return *r;
}

std::expected<void, ClientError> Client::receiveMessage(int64_t deadlineNs, std::span<const uint8_t>& frame) {
  // Drop the previous message, keeping whatever followed it.
  if (frameSize_ > 0) {
    std::memmove(rx_.data(), rx_.data() + frameSize_, rxUsed_ - frameSize_);
    rxUsed_ -= frameSize_;
    frameSize_ = 0;
  }
  while (true) {
    FrameScan scan = scanFrame({rx_.data(), rxUsed_}, config_.maxResponseBytes);
    if (scan.status == FrameStatus::Complete) {
      frameSize_ = scan.size;
      frame = {rx_.data(), frameSize_};
      if (messageTypeOf(frame) != MessageType::Error) return {};
      Reader r(frame.subspan(kMessageHeaderSize));
      uint32_t status = 0;
      std::string reason;
      (void)(r.u32(status) && decode(r, reason));
      return std::unexpected(lost("the server sent ERR " + statusName(status) + (reason.empty() ? "" : ": " + reason)));
    }
    if (scan.status == FrameStatus::Malformed) return std::unexpected(lost("a malformed message from the server"));
    if (rxUsed_ == rx_.size()) rx_.resize(rx_.size() * 2);  // a message longer than any before
    auto n = net::receiveSome(fd_, {rx_.data() + rxUsed_, rx_.size() - rxUsed_}, deadlineNs);
    if (!n) return std::unexpected(lost(n.error()));
    if (*n == 0) return std::unexpected(lost("the server closed the connection"));
    rxUsed_ += *n;
  }
}

std::expected<void, ClientError> Client::transact(uint32_t requestId, int64_t deadlineNs) {
  body_.clear();
  bodyStart_ = 0;
  while (true) {
    std::span<const uint8_t> frame;
    if (auto got = receiveMessage(deadlineNs, frame); !got) return got;
    auto taken = takeChunk(frame, requestId);
    if (!taken) return std::unexpected(taken.error());
    if (*taken) return {};
  }
}

std::expected<bool, ClientError> Client::takeChunk(std::span<const uint8_t> frame, uint32_t requestId) {
  const MessageType type = messageTypeOf(frame);
  const char chunk = static_cast<char>(frame[3]);
  Reader r(frame.subspan(kMessageHeaderSize));
  uint32_t channel = 0, token = 0, sequence = 0, id = 0;
  std::span<const uint8_t> sequenced;  // the sequence header and the body, opened if secured
  if (type == MessageType::Open) {
    std::string policy;
    ByteString certificate, thumbprint;
    if (!r.u32(channel) || !decode(r, policy) || !decode(r, certificate) || !decode(r, thumbprint))
      return std::unexpected(lost("a malformed OPN header"));
    sequenced = r.rest();
    if (mode_ != SecurityMode::None &&
        (!std::ranges::equal(certificate.view(), asymmetric_.peerCertificate) ||
         !openAsymmetric(frame, frame.size() - r.rest().size(), asymmetric_, scratch_, sequenced)))
      return std::unexpected(lost("the OpenSecureChannel response is not signed with the endpoint's certificate or not encrypted for ours"));
  } else if (type == MessageType::Message) {
    if (!r.u32(channel) || !r.u32(token)) return std::unexpected(lost("a malformed MSG header"));
    sequenced = r.rest();
    // The frame is the start of rx_, which is ours to decrypt in place.
    if (mode_ != SecurityMode::None &&
        ((token != tokenId_ && token != previousTokenId_) ||
         !openSymmetric(std::span(rx_.data(), frame.size()), mode_, token == tokenId_ ? serverKeys_ : previousServerKeys_, sequenced)))
      return std::unexpected(lost("a MSG chunk not signed (or encrypted) with the channel's keys"));
  } else {
    return std::unexpected(lost("an unexpected message from the server"));
  }
  Reader s(sequenced);
  if (!s.u32(sequence) || !s.u32(id)) return std::unexpected(lost("a malformed sequence header"));
  if (mode_ != SecurityMode::None && lastServerSequence_ != 0 && !sequenceNumberFollows(lastServerSequence_, sequence))
    return std::unexpected(lost("the server's sequence numbers are out of order"));
  lastServerSequence_ = sequence;
  const bool parked = id == postedId_ && id != requestId;
  if (id != requestId && !parked) return false;  // a late answer to an earlier request
  if (chunk == 'A') return std::unexpected(lost("the server aborted its response"));
  std::vector<uint8_t>& into = parked ? parked_ : body_;
  auto payload = s.rest();
  if (into.size() + payload.size() > config_.maxResponseBytes) return std::unexpected(lost("a response over the size limit"));
  into.insert(into.end(), payload.begin(), payload.end());
  if (chunk != 'F') return false;
  if (parked) parkedDone_ = true;
  return !parked;
}

}  // namespace virtcom::proto::opcua
