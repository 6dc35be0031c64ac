// virtcom_ads_bench's OPC UA half: the counterparts of ads/read_by_handle and ads/notification
// on the same table (protocol_bench.hpp), served by virtcom's OPC UA server and asked by
// virtcom's own client on loopback (docs/performance.md, section OPC UA against ADS):
//   opcua/read           one Read service of MAIN.v7's Value (proto/opcua/client.hpp), as a
//                        round trip: request encoded, sent, answered, its DataValue read
//   opcua/notification   latency from publishSnapshot (the end of a scan that changed MAIN.v0)
//                        to its DataChangeNotification on the bus of the cell's client bridge
//                        (proto/opcua/client_bridge: subscribed, one Publish always posted),
//                        with the publishing and sampling intervals at the server's minimum
//                        (1 ms); the bridge is polled every 20 µs of real time. A PLC's
//                        change falls anywhere in the server's publishing cycle: each one
//                        waits a pseudo-random 0..1 ms first (not timed), else every change
//                        would come just after a publish and wait a whole interval
// p50_us and p99_us are the round trips' median and 99th percentile, as in bench_ads.cpp.
#include <benchmark/benchmark.h>

#include <chrono>
#include <memory>
#include <random>
#include <thread>
#include <vector>

#include "protocol_bench.hpp"
#include "proto/opcua/client.hpp"
#include "proto/opcua/client_bridge.hpp"
#include "proto/opcua/raw_values.hpp"
#include "proto/opcua/server.hpp"
#include "proto/opcua/services.hpp"

namespace ua = virtcom::proto::opcua;

namespace {

using virtcom::bench::kFirstOffset;
using virtcom::bench::RoundTrips;
constexpr uint32_t kReadRequestId = 631, kReadResponseId = 634;

struct UaSetup {
  std::unique_ptr<ua::Server> server;
  std::vector<uint8_t> image = std::vector<uint8_t>(1024, 0);
  ua::ClientConfig client;
};

bool startServer(UaSetup& s, benchmark::State& state) {
  ua::ServerConfig config;
  config.listen = {0x7f000001, 0};
  auto server = ua::Server::start(config, virtcom::bench::table());
  if (!server) {
    state.SkipWithError(server.error().c_str());
    return false;
  }
  s.server = std::move(*server);
  s.server->publishSnapshot(s.image);
  s.client.server = s.server->endpoint();
  s.client.endpointUrl = s.server->endpointUrl();
  return true;
}

std::string nodeOf(const std::string& variable) { return "ns=4;s=|var|virtcom.Application." + variable; }

void read(benchmark::State& state) {
  UaSetup s;
  if (!startServer(s, state)) return;
  ua::Client client(s.client);
  if (auto up = client.connect(); !up) return state.SkipWithError(up.error().text.c_str());
  std::vector<uint8_t> node;
  ua::Writer encoded(node);
  ua::encode(encoded, *ua::parseNodeId(nodeOf("MAIN.v7")));
  RoundTrips trips;
  virtcom::bench::ProcessCpu cpu;
  for (auto _ : state) {
    auto started = trips.start();
    ua::Writer& w = client.beginRequest(kReadRequestId);
    ua::encode(w, 0.0);  // MaxAge
    w.u32(ua::kTimestampsNeither);
    w.i32(1);
    ua::encodeReadValueId(w, node, ua::kValueAttr);
    auto reply = client.call(kReadResponseId);
    uint32_t count = 0;
    ua::RawValue value;
    if (!reply || !reply->arrayLength(count, 1) || count != 1 || !ua::readRawValue(*reply, value) || value.bytes.size() != 4)
      return state.SkipWithError("read failed");
    trips.stop(started);
  }
  state.SetItemsProcessed(state.iterations());
  trips.report(state);
  cpu.report(state, static_cast<double>(state.iterations()));
}

void notification(benchmark::State& state) {
  UaSetup s;
  if (!startServer(s, state)) return;
  virtcom::TagBus bus;
  ua::BridgeConfig config;
  config.client = s.client;
  config.pollNs = 0;  // asks for a 1 ms publishing interval; the server revises it to its minimum
  config.signals.push_back({nodeOf("MAIN.v0"), "MAIN.v0", "Device.in", bus.add("Device.in", virtcom::ElemType::Dint), false, false});
  ua::ClientBridge::StartReport report;
  auto bridge = ua::ClientBridge::start(config, bus, report);
  if (!bridge || !bridge->subscribed()) return state.SkipWithError(report.problems.empty() ? "not subscribed" : report.problems[0].text.c_str());
  const virtcom::TagId tag = bridge->tag(0);
  RoundTrips trips;
  std::minstd_rand phases(17);
  std::uniform_int_distribution<int> phaseUs(0, 1'000);
  int32_t value = 0;
  for (auto _ : state) {
    std::this_thread::sleep_for(std::chrono::microseconds(phaseUs(phases)));
    ++value;
    for (int i = 0; i < 4; ++i) s.image[kFirstOffset + i] = static_cast<uint8_t>(static_cast<uint32_t>(value) >> (8 * i));
    auto started = trips.start();
    s.server->publishSnapshot(s.image);
    while (bus.getInt(tag) != value) {
      if (!bridge->pull(bus, 0)) return state.SkipWithError(bridge->failure().c_str());
      std::this_thread::sleep_for(std::chrono::microseconds(20));
    }
    trips.stop(started);
  }
  trips.report(state);
}

}  // namespace

BENCHMARK(read)->Name("opcua/read")->UseRealTime()->MinTime(1.0);
BENCHMARK(notification)->Name("opcua/notification")->UseRealTime()->MinTime(5.0);
