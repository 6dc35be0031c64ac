#include "proto/opcua/channel.hpp"

#include <algorithm>
#include <ctime>

#include "proto/opcua/crypto.hpp"
#include "proto/opcua/pki.hpp"
#include "proto/opcua/transport.hpp"

namespace virtcom::proto::opcua {

namespace {

// Channel token lifetimes the server grants (ms).
constexpr uint32_t kMinLifetimeMs = 10'000, kMaxLifetimeMs = 3'600'000;

void encodeResponseHeader(Writer& w, uint32_t requestHandle, uint32_t serviceResult) {
  encode(w, dateTimeNow());
  w.u32(requestHandle);
  w.u32(serviceResult);
  w.u8(0);                  // ServiceDiagnostics: empty DiagnosticInfo
  w.i32(0);                 // StringTable
  encode(w, ExtensionObject{});  // AdditionalHeader
}

}  // namespace

bool Channel::fail(std::vector<uint8_t>& tx, StatusCodeValue status, const char* reason) {
  Writer w(tx);
  writeError(w, static_cast<uint32_t>(status), reason);
  return false;
}

bool Channel::handleFrame(std::span<const uint8_t> frame, std::vector<uint8_t>& tx, int64_t nowNs) {
  const MessageType type = messageTypeOf(frame);
  const char chunk = static_cast<char>(frame[3]);
  auto body = frame.subspan(kMessageHeaderSize);
  if (type == MessageType::Hello) return onHello(body, tx);
  if (!hello_) return fail(tx, StatusCodeValue::BadTcpMessageTypeInvalid, "the first message must be HEL");
  if (chunk != 'F' && !(type == MessageType::Message && (chunk == 'C' || chunk == 'A')))
    return fail(tx, StatusCodeValue::BadTcpMessageTypeInvalid, "chunk type must be F (C and A only for MSG)");
  switch (type) {
    case MessageType::Open: return onOpen(frame, tx);
    case MessageType::Message: return onMessage(chunk, frame, tx, nowNs);
    case MessageType::Close: return false;
    default: return fail(tx, StatusCodeValue::BadTcpMessageTypeInvalid, "unexpected message type");
  }
}

bool Channel::onHello(std::span<const uint8_t> body, std::vector<uint8_t>& tx) {
  Hello h;
  if (hello_) return fail(tx, StatusCodeValue::BadTcpMessageTypeInvalid, "a second HEL");
  if (!decodeHello(body, h)) return fail(tx, StatusCodeValue::BadTcpInternalError, "malformed HEL");
  if (h.receiveBufferSize < kMinBufferSize || h.sendBufferSize < kMinBufferSize)
    return fail(tx, StatusCodeValue::BadTcpInternalError, "buffer sizes below 8192");
  hello_ = true;
  peerReceiveBuffer_ = h.receiveBufferSize;
  peerMaxMessage_ = h.maxMessageSize;
  const ServerConfig& c = core_.config();
  Writer w(tx);
  const size_t start = beginMessage(w, "ACK");
  w.u32(kProtocolVersion);
  w.u32(c.receiveBufferBytes);
  w.u32(std::min(c.receiveBufferBytes, h.receiveBufferSize));
  w.u32(c.maxMessageBytes);
  w.u32(0);  // MaxChunkCount: no limit beyond the message size
  finishMessage(w, start);
  return true;
}

bool Channel::onOpen(std::span<const uint8_t> frame, std::vector<uint8_t>& tx) {
  Reader r(frame.subspan(kMessageHeaderSize));
  uint32_t channelId = 0, sequence = 0, requestId = 0;
  std::string policy;
  ByteString certificate, thumbprint;
  if (!r.u32(channelId) || !decode(r, policy) || !decode(r, certificate) || !decode(r, thumbprint))
    return fail(tx, StatusCodeValue::BadDecodingError, "malformed OPN header");
  const bool secured = policy == kSecurityPolicyBasic256Sha256;
  if (!secured && policy != kSecurityPolicyNone)
    return fail(tx, StatusCodeValue::BadSecurityPolicyRejected, "security policy not served (None and Basic256Sha256 are)");
  if (channelId_ != 0 && secured != (mode_ != SecurityMode::None))
    return fail(tx, StatusCodeValue::BadSecurityPolicyRejected, "a renewal must keep the channel's security policy");
  std::span<const uint8_t> plain = r.rest();
  if (secured && !openSecured(frame, frame.size() - r.rest().size(), certificate, thumbprint, plain, tx)) return false;
  Reader body(plain);
  if (!body.u32(sequence) || !body.u32(requestId)) return fail(tx, StatusCodeValue::BadDecodingError, "malformed OPN header");
  if (secured && channelId_ != 0 && !sequenceFollows(sequence))
    return fail(tx, StatusCodeValue::BadSequenceNumberInvalid, "sequence number out of order");
  lastSequence_ = sequence;
  NodeId typeId;
  RequestHeader header;
  uint32_t clientVersion = 0, requestType = 0, mode = 0, lifetime = 0;
  ByteString nonce;
  if (!decode(body, typeId) || typeId != NodeId::num(0, kOpenSecureChannelRequestId) || !decode(body, header) ||
      !body.u32(clientVersion) || !body.u32(requestType) || !body.u32(mode) || !decode(body, nonce) || !body.u32(lifetime))
    return fail(tx, StatusCodeValue::BadDecodingError, "malformed OpenSecureChannel request");
  const auto asked = static_cast<SecurityMode>(mode);
  // A None channel is always open for discovery (GetEndpoints, FindServers: OPC 10000-4 §5.4);
  // CreateSession refuses it unless None is offered.
  if (secured == (asked == SecurityMode::None) || (secured && !core_.offers(asked)) || (channelId_ != 0 && asked != mode_))
    return fail(tx, StatusCodeValue::BadSecurityModeRejected, "security mode not offered by an endpoint (--opcua-security)");
  if (requestType == kSecureChannelIssue && channelId_ == 0) {
    channelId_ = core_.newChannelId();
  } else if (requestType != kSecureChannelRenew || channelId != channelId_ || channelId_ == 0) {
    return fail(tx, StatusCodeValue::BadRequestTypeInvalid, "OpenSecureChannel: issue once, then renew that channel");
  }
  mode_ = asked;
  std::array<uint8_t, kSecureNonceBytes> serverNonce{};
  if (secured && !renewKeys(nonce, serverNonce))
    return fail(tx, StatusCodeValue::BadNonceInvalid, "the client nonce must be 32 bytes (Basic256Sha256)");
  previousTokenId_ = tokenId_;
  tokenId_ = core_.newTokenId();
  body_.clear();
  Writer w(body_);
  encode(w, NodeId::num(0, kOpenSecureChannelResponseId));
  encodeResponseHeader(w, header.requestHandle, 0);
  w.u32(kProtocolVersion);
  w.u32(channelId_);
  w.u32(tokenId_);
  encode(w, dateTimeNow());
  w.u32(std::clamp(lifetime ? lifetime : kMaxLifetimeMs, kMinLifetimeMs, kMaxLifetimeMs));
  if (secured) encode(w, ByteString{std::string(serverNonce.begin(), serverNonce.end())});
  else w.i32(0);  // ServerNonce: none with policy None
  Writer out(tx);
  const size_t start = beginMessage(out, "OPN");
  out.u32(channelId_);
  if (!secured) {
    out.string(kSecurityPolicyNone);
    out.nullString();  // SenderCertificate
    out.nullString();  // ReceiverCertificateThumbprint
  } else {
    out.string(kSecurityPolicyBasic256Sha256);
    encode(out, ByteString{std::string(asymmetric_.ownCertificate.begin(), asymmetric_.ownCertificate.end())});
    std::array<uint8_t, 20> peerThumbprint{};
    crypto().sha1(asymmetric_.peerCertificate.data(), asymmetric_.peerCertificate.size(), peerThumbprint.data());
    encode(out, ByteString{std::string(peerThumbprint.begin(), peerThumbprint.end())});
  }
  const size_t headerEnd = tx.size();
  out.u32(++sequence_);
  out.u32(requestId);
  out.raw(body_);
  finishMessage(out, start);
  if (secured && !sealAsymmetric(tx, start, headerEnd, asymmetric_)) {
    tx.resize(start);
    return fail(tx, StatusCodeValue::BadSecurityChecksFailed, "could not sign or encrypt the OpenSecureChannel response");
  }
  return true;
}

bool Channel::openSecured(std::span<const uint8_t> frame, size_t headerEnd, const ByteString& certificate, const ByteString& thumbprint,
                          std::span<const uint8_t>& plain, std::vector<uint8_t>& tx) {
  const Pki* pki = core_.config().pki.get();
  if (!pki) return fail(tx, StatusCodeValue::BadSecurityPolicyRejected, "security policy not served (--opcua-security none)");
  if (!std::ranges::equal(thumbprint.view(), pki->thumbprint))
    return fail(tx, StatusCodeValue::BadSecurityChecksFailed, "the receiver thumbprint is not this server's certificate");
  if (channelId_ != 0) {
    if (!std::ranges::equal(certificate.view(), asymmetric_.peerCertificate))
      return fail(tx, StatusCodeValue::BadSecurityChecksFailed, "a renewal must come with the channel's client certificate");
  } else {
    const PeerCheck check = checkPeerCertificate(*pki, certificate.view(), ::time(nullptr));
    if (check.trust != PeerTrust::Trusted) {
      rejection_ = check.message;
      // BadSecurityChecksFailed, not the reason: OPC 10000-4 §5.5.2 asks not to tell the peer why.
      return fail(tx, StatusCodeValue::BadSecurityChecksFailed, "client certificate refused");
    }
    asymmetric_.ownCertificate = pki->certificate;
    asymmetric_.ownKeyPem = pki->keyPem;
    asymmetric_.peerCertificate.assign(certificate.view().begin(), certificate.view().end());
  }
  if (!openAsymmetric(frame, headerEnd, asymmetric_, scratch_, plain))
    return fail(tx, StatusCodeValue::BadSecurityChecksFailed, "the OpenSecureChannel request is not signed by its certificate or not "
                                                              "encrypted for this server's");
  return true;
}

bool Channel::renewKeys(const ByteString& clientNonce, std::array<uint8_t, kSecureNonceBytes>& serverNonce) {
  if (clientNonce.bytes.size() != kSecureNonceBytes || !crypto().randomBytes(serverNonce.data(), serverNonce.size())) return false;
  const auto client = clientNonce.view();
  previousClientKeys_ = clientKeys_;
  // OPC 10000-6 §6.7.5: the client's keys from P_SHA256(ServerNonce, ClientNonce), the server's
  // from P_SHA256(ClientNonce, ServerNonce).
  return deriveKeys(serverNonce, client, clientKeys_) && deriveKeys(client, serverNonce, serverKeys_);
}

bool Channel::sequenceFollows(uint32_t sequence) { return sequenceNumberFollows(lastSequence_, sequence); }

bool Channel::onMessage(char chunk, std::span<const uint8_t> frame, std::vector<uint8_t>& tx, int64_t nowNs) {
  Reader r(frame.subspan(kMessageHeaderSize));
  uint32_t channelId = 0, tokenId = 0, sequence = 0, requestId = 0;
  if (!r.u32(channelId) || !r.u32(tokenId)) return fail(tx, StatusCodeValue::BadDecodingError, "malformed MSG header");
  if (channelId_ == 0 || channelId != channelId_) return fail(tx, StatusCodeValue::BadTcpSecureChannelUnknown, "no such secure channel");
  if (tokenId != tokenId_ && tokenId != previousTokenId_) return fail(tx, StatusCodeValue::BadSecureChannelIdInvalid, "unknown token id");
  std::span<const uint8_t> sequenced = r.rest();
  if (mode_ != SecurityMode::None) {
    rx_.assign(frame.begin(), frame.end());
    if (!openSymmetric(rx_, mode_, tokenId == tokenId_ ? clientKeys_ : previousClientKeys_, sequenced))
      return fail(tx, StatusCodeValue::BadSecurityChecksFailed, "MSG chunk not signed (or encrypted) with the channel's keys");
  }
  Reader s(sequenced);
  if (!s.u32(sequence) || !s.u32(requestId)) return fail(tx, StatusCodeValue::BadDecodingError, "malformed MSG header");
  if (mode_ != SecurityMode::None && !sequenceFollows(sequence))
    return fail(tx, StatusCodeValue::BadSequenceNumberInvalid, "sequence number out of order");
  lastSequence_ = sequence;
  if (chunk == 'A') {
    partial_.clear();
    return true;
  }
  auto payload = s.rest();
  if (partial_.size() + payload.size() > core_.config().maxMessageBytes)
    return fail(tx, StatusCodeValue::BadRequestTooLarge, "request larger than the server's MaxMessageSize");
  partial_.insert(partial_.end(), payload.begin(), payload.end());
  if (chunk == 'C') return true;
  const Reply reply = serve(partial_, requestId, nowNs);
  partial_.clear();
  if (reply == Reply::Close) return false;
  if (reply == Reply::Send) sendChunks("MSG", requestId, tx);
  return true;
}

void Channel::tick(int64_t nowNs, std::vector<uint8_t>& tx) {
  if (channelId_ == 0) return;
  for (Session& s : core_.sessions())
    if (s.channelId == channelId_ && s.activated)
      runSubscriptions(core_, s, nowNs, body_, [&](uint32_t requestId) { sendChunks("MSG", requestId, tx); });
}

int64_t Channel::nextDueNs() {
  int64_t due = INT64_MAX;
  if (channelId_ == 0) return due;
  for (const Session& s : core_.sessions())
    if (s.channelId == channelId_ && s.activated) due = std::min(due, nextSubscriptionDueNs(s));
  return due;
}

Channel::Reply Channel::serve(std::span<const uint8_t> request, uint32_t requestId, int64_t nowNs) {
  body_.clear();
  Writer w(body_);
  Reader r(request);
  NodeId typeId;
  RequestHeader header;
  if (!decode(r, typeId)) {
    encode(w, NodeId::num(0, kServiceFaultId));
    encodeResponseHeader(w, 0, static_cast<uint32_t>(StatusCodeValue::BadDecodingError));
    return Reply::Send;
  }
  if (typeId == NodeId::num(0, kCloseSecureChannelRequestId)) return Reply::Close;
  const bool headerOk = decode(r, header);
  const ServiceEntry* service = typeId.ns == 0 && typeId.kind == NodeId::Kind::Numeric ? findService(typeId.numeric) : nullptr;
  ServiceContext ctx{core_, channelId_, nullptr, nowNs, requestId, header.requestHandle, mode_, asymmetric_.peerCertificate};
  uint32_t status = !headerOk ? static_cast<uint32_t>(StatusCodeValue::BadDecodingError)
                    : !service ? static_cast<uint32_t>(StatusCodeValue::BadServiceUnsupported)
                               : 0;
  if (status == 0 && service->access != ServiceAccess::Channel) {
    ctx.session = core_.findSession(header.authenticationToken);
    if (!ctx.session) status = static_cast<uint32_t>(StatusCodeValue::BadSessionIdInvalid);
    else if (service->access == ServiceAccess::Active && !ctx.session->activated)
      status = static_cast<uint32_t>(StatusCodeValue::BadSessionNotActivated);
    else if (service->access == ServiceAccess::Active && ctx.session->channelId != channelId_)
      status = static_cast<uint32_t>(StatusCodeValue::BadSecureChannelIdInvalid);
    else ctx.session->lastUsedNs = nowNs;
  }
  if (status == 0) {
    encode(w, NodeId::num(0, service->responseId));
    encodeResponseHeader(w, header.requestHandle, 0);
    status = service->handler(ctx, r, w);
    if (status == kDeferredResponse) {
      body_.clear();
      return Reply::Later;
    }
    if (status == 0 && peerMaxMessage_ != 0 && body_.size() > peerMaxMessage_)
      status = static_cast<uint32_t>(StatusCodeValue::BadResponseTooLarge);
    if (status == 0) return Reply::Send;
    body_.clear();
  }
  encode(w, NodeId::num(0, kServiceFaultId));
  encodeResponseHeader(w, header.requestHandle, status);
  return Reply::Send;
}

void Channel::sendChunks(const char* type, uint32_t requestId, std::vector<uint8_t>& tx) {
  const size_t buffer = std::max<size_t>(peerReceiveBuffer_, kMinBufferSize);
  const size_t room = symmetricChunkRoom(buffer, mode_);
  std::span<const uint8_t> rest(body_);
  Writer out(tx);
  do {
    auto part = rest.first(std::min(room, rest.size()));
    rest = rest.subspan(part.size());
    const size_t start = beginMessage(out, type, rest.empty() ? 'F' : 'C');
    out.u32(channelId_);
    out.u32(tokenId_);
    out.u32(++sequence_);
    out.u32(requestId);
    out.raw(part);
    finishMessage(out, start);
    // Sealing fails only if libcrypto does: nothing is sent then, rather than a chunk in clear.
    if (mode_ != SecurityMode::None && !sealSymmetric(tx, start, mode_, serverKeys_)) {
      tx.resize(start);
      return;
    }
  } while (!rest.empty());
}

}  // namespace virtcom::proto::opcua
