#pragma once
// Test-only: an ADS client that behaves as Beckhoff's AdsLib (github Beckhoff/ADS) does on the
// wire, for the e2e tests (AdsLib itself is not in Debian):
//  - its AMS port is fixed per process (AdsLib's router hands out 30000 first), so a new
//    connection from the next "process" is the same AMS route;
//  - handles by name with readLength 4 and names without NUL; values by handle (0xF005);
//  - notifications by handle (IG 0xF005), and the callback registered only once the
//    AddDeviceNotification reply has been taken: a sample that arrived with the reply (same
//    recv) is dropped, as AdsLib's dispatcher drops samples of unknown handles.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace virtcom::e2e {

class AdsLibStyleClient {
 public:
  using Bytes = std::vector<uint8_t>;
  struct Reply {
    uint32_t result = 0xFFFFFFFF;  // the ADS result, or 0xFFFFFFFF if no reply came
    Bytes data;                    // Read / ReadWrite: the data after result and length
  };

  // Connects to 127.0.0.1:tcpPort; receives give up after 5 s, so a server bug fails a test.
  AdsLibStyleClient(int tcpPort, uint16_t amsPort = 30000) : amsPort_(amsPort) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    timeval timeout{5, 0};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(static_cast<uint16_t>(tcpPort));
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = ::connect(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0;
  }
  ~AdsLibStyleClient() { ::close(fd_); }
  AdsLibStyleClient(const AdsLibStyleClient&) = delete;
  AdsLibStyleClient& operator=(const AdsLibStyleClient&) = delete;
  bool connected() const { return connected_; }

  Reply read(uint32_t ig, uint32_t io, uint32_t length) { return call(2, u32s({ig, io, length})); }
  Reply readWrite(uint32_t ig, uint32_t io, uint32_t readLength, const Bytes& data) {
    Bytes d = u32s({ig, io, readLength, static_cast<uint32_t>(data.size())});
    d.insert(d.end(), data.begin(), data.end());
    return call(9, d);
  }
  Reply write(uint32_t ig, uint32_t io, const Bytes& data) {
    Bytes d = u32s({ig, io, static_cast<uint32_t>(data.size())});
    d.insert(d.end(), data.begin(), data.end());
    return call(3, d);
  }
  // AdsLib's handle by name: readLength 4, the name without NUL. nullopt on error.
  std::optional<uint32_t> handle(const std::string& name) {
    Reply r = readWrite(0xF003, 0, 4, Bytes(name.begin(), name.end()));
    if (r.result != 0 || r.data.size() != 4) return std::nullopt;
    return get32(r.data, 0);
  }
  uint32_t release(uint32_t handle) { return write(0xF006, 0, u32s({handle})).result; }

  // AddDeviceNotification on change (mode 4) of `length` bytes by handle; the notification
  // handle, or nullopt on error. Samples received with the reply are lost (see above).
  std::optional<uint32_t> notifyByHandle(uint32_t handle, uint32_t length) {
    Reply r = call(6, u32s({0xF005, handle, length, 4, 0, 0, 0, 0, 0, 0}));
    if (r.result != 0 || r.data.size() < 4) return std::nullopt;
    const uint32_t h = get32(r.data, 0);
    lost_ += samples_.size();
    samples_.clear();
    return h;
  }
  // The next sample of any registered notification (its data), waiting for it; nullopt on timeout.
  std::optional<Bytes> nextSample() {
    while (samples_.empty())
      if (!receiveChunk()) return std::nullopt;
    Bytes s = samples_.front();
    samples_.erase(samples_.begin());
    return s;
  }
  size_t lostSamples() const { return lost_; }

  static Bytes u32s(std::initializer_list<uint32_t> values) {
    Bytes out;
    for (uint32_t v : values)
      for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
    return out;
  }
  static uint32_t get32(const Bytes& b, size_t at) {
    return b[at] | b[at + 1] << 8 | b[at + 2] << 16 | static_cast<uint32_t>(b[at + 3]) << 24;
  }

 private:
  static constexpr size_t kHeader = 38;  // AMS/TCP (6) + AMS header (32)

  Reply call(uint16_t command, const Bytes& data) {
    const uint32_t invoke = ++invokeId_;
    Bytes f{0, 0};
    append32(f, static_cast<uint32_t>(32 + data.size()));
    for (uint8_t b : {127, 0, 0, 1, 1, 1, 0x53, 0x03, 10, 0, 0, 2, 1, 1}) f.push_back(b);
    f.push_back(static_cast<uint8_t>(amsPort_));
    f.push_back(static_cast<uint8_t>(amsPort_ >> 8));
    f.push_back(static_cast<uint8_t>(command));
    f.push_back(0);
    f.push_back(4);
    f.push_back(0);
    append32(f, static_cast<uint32_t>(data.size()));
    append32(f, 0);
    append32(f, invoke);
    f.insert(f.end(), data.begin(), data.end());
    if (::send(fd_, f.data(), f.size(), MSG_NOSIGNAL) != static_cast<ssize_t>(f.size())) return {};
    while (true) {
      for (size_t i = 0; i < replies_.size(); ++i) {
        if (get32(replies_[i], 34) != invoke) continue;
        Bytes frame = std::move(replies_[i]);
        replies_.erase(replies_.begin() + static_cast<ptrdiff_t>(i));
        return parse(command, frame);
      }
      if (!receiveChunk()) return {};
    }
  }

  static Reply parse(uint16_t command, const Bytes& frame) {
    Reply r;
    if (frame.size() < kHeader + 4) return r;
    r.result = get32(frame, kHeader);
    const bool withLength = command == 2 || command == 9;
    if (withLength && frame.size() >= kHeader + 8) r.data.assign(frame.begin() + kHeader + 8, frame.end());
    if (!withLength) r.data.assign(frame.begin() + kHeader + 4, frame.end());
    return r;
  }

  // One recv (the segments that arrived together): its whole frames go to replies_ or samples_
  // (one per sample of a notification). False on close or timeout.
  bool receiveChunk() {
    uint8_t chunk[64 * 1024];
    const ssize_t n = ::recv(fd_, chunk, sizeof chunk, 0);
    if (n <= 0) return false;
    rx_.insert(rx_.end(), chunk, chunk + n);
    while (rx_.size() >= 6 && rx_.size() >= 6 + get32(rx_, 2)) {
      Bytes frame(rx_.begin(), rx_.begin() + 6 + get32(rx_, 2));
      rx_.erase(rx_.begin(), rx_.begin() + static_cast<ptrdiff_t>(frame.size()));
      if (frame.size() < kHeader) continue;
      if ((frame[22] | frame[23] << 8) == 8) {
        // Stream: length, stamps; per stamp: time, samples; per sample: handle, size, data.
        if (frame.size() < kHeader + 8 + 12) continue;
        size_t at = kHeader + 8 + 8;
        const uint32_t samples = get32(frame, at);
        at += 4;
        for (uint32_t i = 0; i < samples && at + 8 <= frame.size(); ++i) {
          const uint32_t size = get32(frame, at + 4);
          if (at + 8 + size > frame.size()) break;
          samples_.emplace_back(frame.begin() + static_cast<ptrdiff_t>(at + 8), frame.begin() + static_cast<ptrdiff_t>(at + 8 + size));
          at += 8 + size;
        }
      } else {
        replies_.push_back(std::move(frame));
      }
    }
    return true;
  }

  static void append32(Bytes& b, uint32_t v) {
    for (int i = 0; i < 4; ++i) b.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }

  int fd_ = -1;
  bool connected_ = false;
  uint16_t amsPort_;
  uint32_t invokeId_ = 0;
  Bytes rx_;
  std::vector<Bytes> replies_, samples_;
  size_t lost_ = 0;
};

}  // namespace virtcom::e2e
