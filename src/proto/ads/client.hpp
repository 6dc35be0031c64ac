#pragma once
// A small blocking ADS client (docs/ads.md, Wire reference): one TCP connection to an AMS router
// (a TwinCAT PC, or `virtcom exec --ads`), one request at a time, each answered within the
// timeout or the link counts as lost. Requests are framed with the server's codec (ams.hpp,
// byte_io.hpp); replies are matched by invoke id, anything else on the stream is skipped.
// Like Beckhoff's AdsLib it sends AMS packets straight away with its own source address (no
// AMS/TCP port registration), so the router must accept that NetId: a TwinCAT needs a route to
// it; virtcom's server accepts any. Used on the simulation thread by the ADS client bridge.
// Allocation: only when a request or reply is larger than any before (reserve() avoids even
// that) and when a failure's text is made.
#include <cstdint>
#include <expected>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "proto/ads/ams.hpp"
#include "proto/net/endpoint.hpp"

namespace virtcom::proto::ads {

struct ClientConfig {
  net::Endpoint router{0x7f000001, 48898};
  AmsAddress target{kLocalAliasNetId, 851};
  // The source address; without one the NetId is the socket's local IPv4 address + ".1.1"
  // (AdsLib's rule: 127.0.0.1.1.1 over loopback).
  std::optional<AmsNetId> localNetId;
  uint16_t localPort = 30000;         // AdsLib's first client port
  int64_t timeoutNs = 500'000'000;    // connect and each request
  size_t maxReplyBytes = 1024 * 1024; // a longer frame is a broken link
};

struct ClientError {
  bool linkLost = true;  // the connection failed and is closed (refused, reset, timeout, garbage)
  uint32_t code = 0;     // else: the ADS error of the reply (result field, or AMS header error)
  std::string text;      // one line, e.g. "0x710 symbol not found" or "connection refused"
};

class Client {
 public:
  explicit Client(ClientConfig config);
  ~Client();  // close()
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  // Opens the TCP connection (within the timeout). Blocks.
  std::expected<void, ClientError> connect();
  void close();
  bool connected() const { return fd_ >= 0; }
  const ClientConfig& config() const { return config_; }
  AmsAddress local() const { return local_; }
  // Grows the buffers so requests of `requestBytes` and replies of `replyBytes` of ADS data
  // need no allocation.
  void reserve(size_t requestBytes, size_t replyBytes);

  // Read (command 2): the data of the reply (at most `length` bytes), valid until the next call.
  std::expected<std::span<const uint8_t>, ClientError> read(uint32_t indexGroup, uint32_t indexOffset, uint32_t length);
  // Write (command 3).
  std::expected<void, ClientError> write(uint32_t indexGroup, uint32_t indexOffset, std::span<const uint8_t> data);
  // ReadWrite (command 9): the data of the reply, valid until the next call.
  std::expected<std::span<const uint8_t>, ClientError> readWrite(uint32_t indexGroup, uint32_t indexOffset,
                                                                 uint32_t readLength, std::span<const uint8_t> data);

  // Requests sent so far.
  uint64_t requests() const { return invokeId_; }

 private:
  // Sends the request whose ADS data is in tx_ after the header space; waits for its reply.
  // The reply's ADS data are rx_[kFrameHeaderSize, replySize_).
  std::expected<std::span<const uint8_t>, ClientError> transact(Command command);
  std::expected<std::span<const uint8_t>, ClientError> dataReply(std::span<const uint8_t> reply, uint32_t maxLength,
                                                                 const char* command);
  std::expected<void, ClientError> sendAll(int64_t deadlineNs);
  std::expected<void, ClientError> receiveFrame(int64_t deadlineNs);
  ClientError lost(std::string what);
  void beginRequest(Command command, size_t dataBytes);  // the AMS/TCP and AMS headers of the next request into tx_

  ClientConfig config_;
  AmsAddress local_;
  int fd_ = -1;
  uint32_t invokeId_ = 0;
  std::vector<uint8_t> tx_, rx_;
  size_t rxUsed_ = 0;     // bytes received into rx_
  size_t frameSize_ = 0;  // the current frame: rx_[0, frameSize_)
};

// "0x710 symbol not found" for an ADS error code.
std::string adsErrorText(uint32_t code);

}  // namespace virtcom::proto::ads
