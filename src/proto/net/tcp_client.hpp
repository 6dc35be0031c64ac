#pragma once
// The blocking side of a protocol client (the ADS and OPC UA client bridges): one non-blocking
// TCP socket driven with deadlines, so that a request either completes or fails within its
// timeout. Nothing here knows a protocol or allocates, except a failure's text.
#include <cstddef>
#include <cstdint>
#include <expected>
#include <span>
#include <string>

#include "proto/net/endpoint.hpp"

namespace virtcom::proto::net {

// Connects to `peer` before `deadlineNs` (monotonic): a non-blocking, close-on-exec socket with
// TCP_NODELAY (one small request per round trip) and SO_KEEPALIVE; else why not ("connection
// refused", "no connection within the timeout").
std::expected<int, std::string> connectTcp(const Endpoint& peer, int64_t deadlineNs);
// Sends every byte of `data` before the deadline.
std::expected<void, std::string> sendAll(int fd, std::span<const uint8_t> data, int64_t deadlineNs);
// Receives at least one byte into `into` before the deadline: how many; 0 when the peer closed
// the connection.
std::expected<size_t, std::string> receiveSome(int fd, std::span<uint8_t> into, int64_t deadlineNs);

}  // namespace virtcom::proto::net
