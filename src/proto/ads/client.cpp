#include "proto/ads/client.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/clock.hpp"
#include "proto/ads/byte_io.hpp"
#include "proto/net/tcp_client.hpp"

namespace virtcom::proto::ads {

namespace {

constexpr uint16_t kResponseFlag = 0x0001;  // state flags bit 0 (docs/ads.md, AMS/TCP and the AMS header)
constexpr size_t kInitialBuffer = 4096;

}  // namespace

std::string adsErrorText(uint32_t code) {
  char hex[16];
  std::snprintf(hex, sizeof hex, "0x%X", code);
  return std::string(hex) + " " + errorText(code);
}

Client::Client(ClientConfig config) : config_(std::move(config)) {
  tx_.reserve(kInitialBuffer);
  rx_.resize(kInitialBuffer);
}

Client::~Client() { close(); }

void Client::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  rxUsed_ = frameSize_ = 0;
}

void Client::reserve(size_t requestBytes, size_t replyBytes) {
  tx_.reserve(kFrameHeaderSize + requestBytes);
  if (rx_.size() < kFrameHeaderSize + replyBytes) rx_.resize(kFrameHeaderSize + replyBytes);
}

ClientError Client::lost(std::string what) {
  close();
  return ClientError{true, 0, std::move(what)};
}

std::expected<void, ClientError> Client::connect() {
  close();
  auto fd = net::connectTcp(config_.router, monotonicNowNs() + config_.timeoutNs);
  if (!fd) return std::unexpected(lost(fd.error()));
  fd_ = *fd;
  local_.port = config_.localPort;
  if (config_.localNetId) {
    local_.netId = *config_.localNetId;
  } else {
    sockaddr_in self{};
    socklen_t len = sizeof self;
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&self), &len);
    uint32_t ip = ntohl(self.sin_addr.s_addr);
    local_.netId = {static_cast<uint8_t>(ip >> 24), static_cast<uint8_t>(ip >> 16), static_cast<uint8_t>(ip >> 8),
                    static_cast<uint8_t>(ip), 1, 1};
  }
  return {};
}

void Client::beginRequest(Command command, size_t dataBytes) {
  AmsHeader h;
  h.commandId = static_cast<uint16_t>(command);
  h.target = config_.target;
  h.source = local_;
  h.stateFlags = state_flags::kNotification;  // 0x0004: an ADS command request
  h.dataLength = static_cast<uint32_t>(dataBytes);
  h.invokeId = invokeId_ + 1;
  tx_.clear();
  writeAmsFrameHeader(tx_, h);
}

std::expected<std::span<const uint8_t>, ClientError> Client::read(uint32_t indexGroup, uint32_t indexOffset, uint32_t length) {
  beginRequest(Command::Read, 12);
  LittleEndianWriter w(tx_);
  w.u32(indexGroup);
  w.u32(indexOffset);
  w.u32(length);
  auto reply = transact(Command::Read);
  if (!reply) return std::unexpected(reply.error());
  return dataReply(*reply, length, "Read");
}

std::expected<void, ClientError> Client::write(uint32_t indexGroup, uint32_t indexOffset, std::span<const uint8_t> data) {
  beginRequest(Command::Write, 12 + data.size());
  LittleEndianWriter w(tx_);
  w.u32(indexGroup);
  w.u32(indexOffset);
  w.u32(static_cast<uint32_t>(data.size()));
  w.bytes(data);
  auto reply = transact(Command::Write);
  if (!reply) return std::unexpected(reply.error());
  auto result = LittleEndianReader(*reply).u32();
  if (!result) return std::unexpected(lost("a Write reply shorter than 4 bytes"));
  if (*result != 0) return std::unexpected(ClientError{false, *result, adsErrorText(*result)});
  return {};
}

std::expected<std::span<const uint8_t>, ClientError> Client::readWrite(uint32_t indexGroup, uint32_t indexOffset,
                                                                       uint32_t readLength, std::span<const uint8_t> data) {
  beginRequest(Command::ReadWrite, 16 + data.size());
  LittleEndianWriter w(tx_);
  w.u32(indexGroup);
  w.u32(indexOffset);
  w.u32(readLength);
  w.u32(static_cast<uint32_t>(data.size()));
  w.bytes(data);
  auto reply = transact(Command::ReadWrite);
  if (!reply) return std::unexpected(reply.error());
  return dataReply(*reply, readLength, "ReadWrite");
}

// A Read or ReadWrite reply: result, length, then at most `maxLength` bytes of data.
std::expected<std::span<const uint8_t>, ClientError> Client::dataReply(std::span<const uint8_t> reply, uint32_t maxLength,
                                                                       const char* command) {
  LittleEndianReader r(reply);
  auto result = r.u32();
  auto size = r.u32();
  if (!result || !size) return std::unexpected(lost(std::string("a ") + command + " reply shorter than 8 bytes"));
  if (*result != 0) return std::unexpected(ClientError{false, *result, adsErrorText(*result)});
  auto data = r.bytes(*size);
  if (!data || *size > maxLength) return std::unexpected(lost(std::string("a ") + command + " reply whose length disagrees with its data"));
  return *data;
}

std::expected<void, ClientError> Client::sendAll(int64_t deadlineNs) {
  if (auto sent = net::sendAll(fd_, tx_, deadlineNs); !sent) return std::unexpected(lost(sent.error()));
  return {};
}

std::expected<void, ClientError> Client::receiveFrame(int64_t deadlineNs) {
  // Drop the previous frame, keeping whatever followed it.
  if (frameSize_ > 0) {
    std::memmove(rx_.data(), rx_.data() + frameSize_, rxUsed_ - frameSize_);
    rxUsed_ -= frameSize_;
    frameSize_ = 0;
  }
  while (true) {
    FrameScan scan = scanFrame({rx_.data(), rxUsed_}, kFrameHeaderSize + config_.maxReplyBytes);
    if (scan.status == FrameStatus::Complete) {
      frameSize_ = scan.size;
      return {};
    }
    if (scan.status == FrameStatus::Malformed) return std::unexpected(lost("a malformed AMS/TCP frame"));
    if (rxUsed_ == rx_.size()) rx_.resize(rx_.size() * 2);  // a frame longer than any before
    auto n = net::receiveSome(fd_, {rx_.data() + rxUsed_, rx_.size() - rxUsed_}, deadlineNs);
    if (!n) return std::unexpected(lost(n.error()));
    if (*n == 0) return std::unexpected(lost("the router closed the connection"));
    rxUsed_ += *n;
  }
}

std::expected<std::span<const uint8_t>, ClientError> Client::transact(Command command) {
  if (fd_ < 0) return std::unexpected(ClientError{true, 0, "not connected"});
  ++invokeId_;
  const int64_t deadline = monotonicNowNs() + config_.timeoutNs;
  if (auto sent = sendAll(deadline); !sent) return std::unexpected(sent.error());
  while (true) {
    if (auto got = receiveFrame(deadline); !got) return std::unexpected(got.error());
    std::span<const uint8_t> frame(rx_.data(), frameSize_);
    if (LittleEndianReader(frame).u16() != static_cast<uint16_t>(AmsTcpCommand::AmsPacket)) continue;  // router notes
    auto h = readAmsHeader(frame);
    if (!h || h->invokeId != invokeId_ || h->commandId != static_cast<uint16_t>(command) || !(h->stateFlags & kResponseFlag))
      continue;  // a notification or a late reply to an earlier request
    if (h->errorCode != 0) return std::unexpected(ClientError{false, h->errorCode, adsErrorText(h->errorCode)});
    return frame.subspan(kFrameHeaderSize);
  }
}

}  // namespace virtcom::proto::ads
