// virtcom_ads_bench: ADS round trips against virtcom's ADS server on loopback, one connection,
// as a client sees them (docs/performance.md, section ADS):
//   ads/read_by_handle   Read 0xF005 of a 4-byte DINT by handle (AdsLib's AdsVariable<DINT>)
//   ads/sum_read_100     one 0xF080 sum read of 100 DINTs
//   ads/notification     latency from publishSnapshot (the end of a scan that changed a value)
//                        to the on-change DeviceNotification arriving at the client
//   ads/bridge_step      one step of the cell's ADS client bridge (proto/ads/client_bridge) with
//                        50 PLC outputs read and 50 device outputs of which one changed: a sum
//                        read and a Write by handle
//   ads/read_by_handle_pipelined  kWindow reads by handle sent at once, then their kWindow
//                        replies (one iteration: kWindow reads; reads/s on one connection)
//   ads/read_by_handle_8_connections  8 connections, one read by handle in flight on each:
//                        sent on all, then all replies received (one iteration: 8 reads)
//   tcp/echo_floor       the loopback floor: a bare TCP echo server thread (poll, recv, send, as
//                        the ADS server's loop) returning a frame of the size of a read's request
// One iteration is one round trip; real time is what counts (the server runs on its own thread).
// The round trips' median and 99th percentile are the counters p50_us and p99_us.
// The same binary measures OPC UA's counterparts of read_by_handle and notification on the same
// table (bench_opcua.cpp), so that one run gives the ratios of docs/performance.md.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

#include <benchmark/benchmark.h>

#include <poll.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <ctime>
#include <cstdlib>
#include <memory>
#include <thread>
#include <vector>

#include "protocol_bench.hpp"
#include "proto/ads/byte_io.hpp"
#include "proto/ads/client_bridge.hpp"
#include "proto/ads/server.hpp"

namespace ads = virtcom::proto::ads;

namespace {

using Bytes = std::vector<uint8_t>;
using virtcom::bench::kFirstOffset;
using virtcom::bench::kVariables;
using virtcom::bench::ProcessCpu;
using virtcom::bench::RoundTrips;
using virtcom::bench::table;

class Connection {
 public:
  explicit Connection(uint16_t port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    int one = 1;
    ::setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(port);
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ok_ = ::connect(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0;
  }
  ~Connection() { ::close(fd_); }
  bool ok() const { return ok_; }
  // Sends `request` (or nothing, if empty) and reads one whole AMS/TCP frame into rx_.
  bool roundTrip(const Bytes& request) { return sendAll(request) && receiveFrame(); }
  bool sendAll(const Bytes& request) {
    return request.empty() || ::send(fd_, request.data(), request.size(), 0) == static_cast<ssize_t>(request.size());
  }
  // One whole AMS/TCP frame into rx_.
  bool receiveFrame() {
    if (!receive(6)) return false;
    const uint32_t length = rx_[2] | rx_[3] << 8 | rx_[4] << 16 | static_cast<uint32_t>(rx_[5]) << 24;
    return receive(length);
  }
  int fd() const { return fd_; }
  uint32_t u32At(size_t offset) const {
    return rx_[offset] | rx_[offset + 1] << 8 | rx_[offset + 2] << 16 | static_cast<uint32_t>(rx_[offset + 3]) << 24;
  }

  // Exactly n bytes into rx_.
  bool receive(size_t n) {
    rx_.resize(n);
    size_t got = 0;
    while (got < n) {
      ssize_t r = ::recv(fd_, rx_.data() + got, n - got, 0);
      if (r <= 0) return false;
      got += static_cast<size_t>(r);
    }
    return true;
  }

 private:
  int fd_ = -1;
  bool ok_ = false;
  Bytes rx_;
};

Bytes request(uint16_t command, const Bytes& data) {
  ads::AmsHeader h;
  h.target = {ads::kLocalAliasNetId, ads::kPlcPort};
  h.source = {{10, 0, 0, 1, 1, 1}, 30000};
  h.commandId = command;
  h.stateFlags = 4;
  h.dataLength = static_cast<uint32_t>(data.size());
  h.invokeId = 1;
  Bytes out;
  ads::writeAmsFrameHeader(out, h);
  out.insert(out.end(), data.begin(), data.end());
  return out;
}

Bytes fields(std::initializer_list<uint32_t> values, const std::string& tail = "") {
  Bytes out;
  ads::LittleEndianWriter w(out);
  for (uint32_t v : values) w.u32(v);
  out.insert(out.end(), tail.begin(), tail.end());
  return out;
}

struct Setup {
  std::unique_ptr<ads::Server> server;
  std::unique_ptr<Connection> client;
  Bytes image = Bytes(1024, 0);
};

bool start(Setup& s, benchmark::State& state) {
  ads::ServerConfig config;
  config.listen.port = 0;
  auto server = ads::Server::start(config, table());
  if (!server) {
    state.SkipWithError(server.error().c_str());
    return false;
  }
  s.server = std::move(*server);
  s.server->publishSnapshot(s.image, ads::kAdsStateRun);
  s.client = std::make_unique<Connection>(s.server->endpoint().port);
  if (!s.client->ok()) state.SkipWithError("cannot connect");
  return s.client->ok();
}

void readByHandle(benchmark::State& state) {
  Setup s;
  if (!start(s, state)) return;
  s.client->roundTrip(request(9, fields({0xF003, 0, 4, 7}, "MAIN.v7")));
  const uint32_t handle = s.client->u32At(46);
  const Bytes read = request(2, fields({0xF005, handle, 4}));
  RoundTrips trips;
  ProcessCpu cpu;
  for (auto _ : state) {
    auto started = trips.start();
    if (!s.client->roundTrip(read)) state.SkipWithError("read failed");
    trips.stop(started);
  }
  state.SetItemsProcessed(state.iterations());
  trips.report(state);
  cpu.report(state, static_cast<double>(state.iterations()));
}

// Reads in flight at once in ads/read_by_handle_pipelined (AdsLib's threads sharing one
// connection, or ads-client's concurrent promises, do the same).
constexpr size_t kWindow = 32;

void readByHandlePipelined(benchmark::State& state) {
  Setup s;
  if (!start(s, state)) return;
  s.client->roundTrip(request(9, fields({0xF003, 0, 4, 7}, "MAIN.v7")));
  const uint32_t handle = s.client->u32At(46);
  const Bytes read = request(2, fields({0xF005, handle, 4}));
  Bytes window;
  for (size_t i = 0; i < kWindow; ++i) window.insert(window.end(), read.begin(), read.end());
  ProcessCpu cpu;
  for (auto _ : state) {
    if (!s.client->sendAll(window)) state.SkipWithError("send failed");
    for (size_t i = 0; i < kWindow; ++i)
      if (!s.client->receiveFrame()) state.SkipWithError("read failed");
  }
  state.SetItemsProcessed(state.iterations() * kWindow);
  cpu.report(state, static_cast<double>(state.iterations() * kWindow));
}

// Client connections reading at once in ads/read_by_handle_8_connections.
constexpr size_t kConnections = 8;

void readByHandle8Connections(benchmark::State& state) {
  Setup s;
  if (!start(s, state)) return;
  std::vector<std::unique_ptr<Connection>> clients;
  Bytes read;
  for (size_t i = 0; i < kConnections; ++i) {
    clients.push_back(std::make_unique<Connection>(s.server->endpoint().port));
    clients.back()->roundTrip(request(9, fields({0xF003, 0, 4, 7}, "MAIN.v7")));
    read = request(2, fields({0xF005, clients.back()->u32At(46), 4}));  // handles are server-wide
  }
  // Each iteration: one request sent on every connection, then every reply received, from
  // this one thread (client threads would measure the scheduler of this 2-core machine).
  bool failed = false;
  ProcessCpu cpu;
  for (auto _ : state) {
    for (auto& c : clients) failed |= !c->sendAll(read);
    for (auto& c : clients) failed |= !c->receiveFrame();
  }
  if (failed) state.SkipWithError("read failed");
  state.SetItemsProcessed(state.iterations() * kConnections);
  cpu.report(state, static_cast<double>(state.iterations() * kConnections));
}

// A bare TCP echo server on loopback: one thread, poll on the listener and its connections,
// recv, send back what came (TCP_NODELAY), as the ADS server's loop does minus the ADS work.
class EchoServer {
 public:
  EchoServer() {
    listen_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof addr;
    ::bind(listen_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr);
    ::listen(listen_, 4);
    ::getsockname(listen_, reinterpret_cast<sockaddr*>(&addr), &len);
    port_ = ntohs(addr.sin_port);
    if (::pipe(stop_) != 0) std::abort();
    thread_ = std::thread([this] { run(); });
  }
  ~EchoServer() {
    const ssize_t woken = ::write(stop_[1], "x", 1);
    if (woken != 1) std::abort();  // the thread would never end
    thread_.join();
    for (int fd : {listen_, stop_[0], stop_[1]}) ::close(fd);
  }
  uint16_t port() const { return port_; }

 private:
  void run() {
    std::vector<pollfd> fds = {{stop_[0], POLLIN, 0}, {listen_, POLLIN, 0}};
    uint8_t buffer[16 * 1024];
    while (::poll(fds.data(), fds.size(), -1) >= 0 && !(fds[0].revents & POLLIN)) {
      for (size_t i = 2; i < fds.size(); ++i) {
        if (!(fds[i].revents & POLLIN)) continue;
        ssize_t n = ::recv(fds[i].fd, buffer, sizeof buffer, 0);
        if (n > 0) ::send(fds[i].fd, buffer, static_cast<size_t>(n), MSG_NOSIGNAL);
      }
      if (fds[1].revents & POLLIN) {
        int fd = ::accept(listen_, nullptr, nullptr);
        int one = 1;
        ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
        fds.push_back({fd, POLLIN, 0});
      }
    }
    for (size_t i = 2; i < fds.size(); ++i) ::close(fds[i].fd);
  }
  int listen_ = -1;
  int stop_[2] = {-1, -1};
  uint16_t port_ = 0;
  std::thread thread_;
};

void tcpEchoFloor(benchmark::State& state) {
  EchoServer echo;
  Connection client(echo.port());
  if (!client.ok()) return state.SkipWithError("cannot connect");
  const Bytes frame = request(2, fields({0xF005, 1, 4}));  // the size of a read by handle
  RoundTrips trips;
  ProcessCpu cpu;
  for (auto _ : state) {
    auto started = trips.start();
    if (!client.sendAll(frame) || !client.receive(frame.size())) state.SkipWithError("echo failed");
    trips.stop(started);
  }
  state.SetItemsProcessed(state.iterations());
  trips.report(state);
  cpu.report(state, static_cast<double>(state.iterations()));
}

void sumRead100(benchmark::State& state) {
  Setup s;
  if (!start(s, state)) return;
  Bytes items;
  ads::LittleEndianWriter w(items);
  for (uint32_t i = 0; i < kVariables; ++i) {
    w.u32(0x4040);
    w.u32(kFirstOffset + 4 * i);
    w.u32(4);
  }
  Bytes data = fields({0xF080, kVariables, 8 * kVariables, static_cast<uint32_t>(items.size())});
  data.insert(data.end(), items.begin(), items.end());
  const Bytes sum = request(9, data);
  for (auto _ : state)
    if (!s.client->roundTrip(sum)) state.SkipWithError("sum read failed");
  state.SetItemsProcessed(state.iterations() * kVariables);
}

void notificationLatency(benchmark::State& state) {
  Setup s;
  if (!start(s, state)) return;
  s.client->roundTrip(request(6, fields({0x4040, kFirstOffset, 4, 4, 0, 0, 0, 0, 0, 0})));
  s.client->roundTrip({});  // the initial sample
  uint32_t value = 0;
  RoundTrips trips;
  for (auto _ : state) {
    ++value;
    for (int i = 0; i < 4; ++i) s.image[kFirstOffset + i] = static_cast<uint8_t>(value >> (8 * i));
    auto started = trips.start();
    s.server->publishSnapshot(s.image, ads::kAdsStateRun);
    if (!s.client->roundTrip({})) state.SkipWithError("no notification");
    trips.stop(started);
  }
  trips.report(state);
}

void bridgeStep(benchmark::State& state) {
  Setup s;
  if (!start(s, state)) return;
  virtcom::TagBus bus;
  ads::BridgeConfig config;
  config.client.router = s.server->endpoint();
  for (uint32_t i = 0; i < kVariables; ++i) {
    const bool toPlc = i >= kVariables / 2;
    std::string port = "Device.port" + std::to_string(i);
    config.signals.push_back({"MAIN.v" + std::to_string(i), port, bus.add(port, virtcom::ElemType::Dint), toPlc, false});
  }
  const virtcom::TagId changing = config.signals.back().tag;
  ads::ClientBridge::StartReport report;
  auto bridge = ads::ClientBridge::start(config, bus, report);
  if (!bridge) {
    state.SkipWithError(report.problems.empty() ? "bridge failed" : report.problems[0].text.c_str());
    return;
  }
  int64_t value = 0;
  for (auto _ : state) {
    if (!bridge->pull(bus, 0)) state.SkipWithError(bridge->failure().c_str());
    bus.setInt(changing, ++value);
    bridge->push(bus, 0);
    s.server->applyPendingWrites({s.image, {}});  // the PLC's next scan takes the write
  }
  if (!bridge->failure().empty()) state.SkipWithError(bridge->failure().c_str());
}

}  // namespace

BENCHMARK(readByHandle)->Name("ads/read_by_handle")->UseRealTime()->MinTime(1.0);
BENCHMARK(sumRead100)->Name("ads/sum_read_100")->UseRealTime()->MinTime(1.0);
BENCHMARK(notificationLatency)->Name("ads/notification")->UseRealTime()->MinTime(1.0);
BENCHMARK(bridgeStep)->Name("ads/bridge_step")->UseRealTime()->MinTime(1.0);
BENCHMARK(readByHandlePipelined)->Name("ads/read_by_handle_pipelined")->UseRealTime()->MinTime(1.0);
BENCHMARK(readByHandle8Connections)->Name("ads/read_by_handle_8_connections")->UseRealTime()->MinTime(1.0);
BENCHMARK(tcpEchoFloor)->Name("tcp/echo_floor")->UseRealTime()->MinTime(1.0);

BENCHMARK_MAIN();
