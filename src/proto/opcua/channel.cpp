#include "proto/opcua/channel.hpp"

#include <algorithm>

#include "proto/opcua/transport.hpp"

namespace virtcom::proto::opcua {

namespace {

// Channel token lifetimes the server grants (ms).
constexpr uint32_t kMinLifetimeMs = 10'000, kMaxLifetimeMs = 3'600'000;
// After the message header: channel id, token id, sequence number, request id.
constexpr size_t kSymmetricHeaderSize = kMessageHeaderSize + 16;

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
    case MessageType::Open: return onOpen(body, tx);
    case MessageType::Message: return onMessage(chunk, body, tx, nowNs);
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

bool Channel::onOpen(std::span<const uint8_t> body, std::vector<uint8_t>& tx) {
  Reader r(body);
  uint32_t channelId = 0, sequence = 0, requestId = 0;
  std::string policy;
  ByteString certificate, thumbprint;
  if (!r.u32(channelId) || !decode(r, policy) || !decode(r, certificate) || !decode(r, thumbprint) || !r.u32(sequence) ||
      !r.u32(requestId))
    return fail(tx, StatusCodeValue::BadDecodingError, "malformed OPN header");
  if (policy != kSecurityPolicyNone)
    return fail(tx, StatusCodeValue::BadSecurityPolicyRejected, "only security policy None is served");
  NodeId typeId;
  RequestHeader header;
  uint32_t clientVersion = 0, requestType = 0, mode = 0, lifetime = 0;
  ByteString nonce;
  if (!decode(r, typeId) || typeId != NodeId::num(0, kOpenSecureChannelRequestId) || !decode(r, header) || !r.u32(clientVersion) ||
      !r.u32(requestType) || !r.u32(mode) || !decode(r, nonce) || !r.u32(lifetime))
    return fail(tx, StatusCodeValue::BadDecodingError, "malformed OpenSecureChannel request");
  if (mode != kSecurityModeNone) return fail(tx, StatusCodeValue::BadSecurityModeRejected, "only security mode None is served");
  if (requestType == kSecureChannelIssue && channelId_ == 0) {
    channelId_ = core_.newChannelId();
  } else if (requestType != kSecureChannelRenew || channelId != channelId_ || channelId_ == 0) {
    return fail(tx, StatusCodeValue::BadRequestTypeInvalid, "OpenSecureChannel: issue once, then renew that channel");
  }
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
  w.i32(0);  // ServerNonce: none with policy None
  Writer out(tx);
  const size_t start = beginMessage(out, "OPN");
  out.u32(channelId_);
  out.string(kSecurityPolicyNone);
  out.nullString();  // SenderCertificate
  out.nullString();  // ReceiverCertificateThumbprint
  out.u32(++sequence_);
  out.u32(requestId);
  out.raw(body_);
  finishMessage(out, start);
  return true;
}

bool Channel::onMessage(char chunk, std::span<const uint8_t> body, std::vector<uint8_t>& tx, int64_t nowNs) {
  Reader r(body);
  uint32_t channelId = 0, tokenId = 0, sequence = 0, requestId = 0;
  if (!r.u32(channelId) || !r.u32(tokenId) || !r.u32(sequence) || !r.u32(requestId))
    return fail(tx, StatusCodeValue::BadDecodingError, "malformed MSG header");
  if (channelId_ == 0 || channelId != channelId_) return fail(tx, StatusCodeValue::BadTcpSecureChannelUnknown, "no such secure channel");
  if (tokenId != tokenId_ && tokenId != previousTokenId_) return fail(tx, StatusCodeValue::BadSecureChannelIdInvalid, "unknown token id");
  if (chunk == 'A') {
    partial_.clear();
    return true;
  }
  auto payload = r.rest();
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
  ServiceContext ctx{core_, channelId_, nullptr, nowNs, requestId, header.requestHandle};
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
  const size_t room = std::max<size_t>(peerReceiveBuffer_, kMinBufferSize) - kSymmetricHeaderSize;
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
  } while (!rest.empty());
}

}  // namespace virtcom::proto::opcua
