// libFuzzer target for what the OPC UA client reads from a server (client.cpp, client_bridge.cpp,
// raw_values.cpp): the input is everything a server sends on one connection (ACK, the
// OpenSecureChannel response, CreateSession, ActivateSession, Read and Write responses,
// ServiceFaults, ERR, chunks, answers to other requests), served on loopback to a client bridge
// wired like a Clamp (docs/devices.md, timed) of examples/ads-cell: it starts (the Read of every
// node's Value and UserAccessLevel), then polls (Read) and writes (Write) until the stream ends;
// then again with a subscription (CreateSubscription, CreateMonitoredItems, Publish responses),
// and with a node named by browse path (a TranslateBrowsePathsToNodeIds response first).
// Finds out-of-bounds reads, unbounded allocation and aborts in the decoding.
// The seeds (corpus/opcua_client) are the streams that an npm node-opcua server
// (tests/e2e/opcua/bridge_plc_server.js) and `virtcom exec --opcua` of examples/ads-cell (with
// and without anonymous writes) sent to a cell of that Clamp, and our server's ERR and
// ServiceFault answers.
#include <cstddef>
#include <cstdint>
#include <span>

#include "proto/opcua/client_bridge.hpp"
#include "support/canned_server.hpp"

namespace ua = virtcom::proto::opcua;
using virtcom::ElemType;
using virtcom::kNoTag;
using virtcom::TagBus;

namespace {

std::string node(const char* path) { return std::string("ns=4;s=|var|virtcom.Application.MAIN.") + path; }

// One bridge against the stream: reading the PLC's outputs each poll, or subscribed to them;
// byPath: programNumber named by browse path.
void runBridge(std::span<const uint8_t> stream, bool subscribe, bool byPath) {
  virtcom::test::CannedServer server(stream);
  TagBus bus;
  const auto program = bus.add("Clamp.programNumber", ElemType::Int), execute = bus.add("Clamp.execute", ElemType::Bool),
             done = bus.add("Clamp.done", ElemType::Bool), error = bus.add("Clamp.error", ElemType::Int),
             busy = bus.add("Clamp.busy", ElemType::Bool);
  ua::BridgeConfig config;
  config.client.server = {0x7f000001, server.port()};
  config.client.endpointUrl = "opc.tcp://127.0.0.1:" + std::to_string(server.port());
  config.pollNs = 0;
  config.subscribe = subscribe;
  config.signals = {{byPath ? "/4:MAIN/4:Clamp.4:programNumber" : node("Clamp.programNumber"), "MAIN.Clamp.programNumber", "Clamp.programNumber", program, false, false},
                    {node("Clamp.execute"), "MAIN.Clamp.execute", "Clamp.execute", execute, false, false},
                    {node("Clamp.done"), "MAIN.Clamp.done", "Clamp.done", done, true, false},
                    {node("Clamp.error"), "MAIN.Clamp.error", "Clamp.error", error, true, false},
                    {node("Clamp.busy"), "MAIN.Clamp.busy", "Clamp.busy", busy, true, false},
                    {node("cycles"), "MAIN.cycles", "", kNoTag, false, true}};
  config.report = [](const std::string&) {};
  ua::ClientBridge::StartReport report;
  auto bridge = ua::ClientBridge::start(std::move(config), bus, report);
  // Every poll writes: the device's done toggles.
  for (int64_t poll = 0; bridge && poll < 64 && bridge->pull(bus, poll); ++poll) {
    bus.setBool(done, poll % 2 == 0);
    bridge->push(bus, poll);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  for (bool subscribe : {false, true}) runBridge({data, size}, subscribe, false);
  runBridge({data, size}, false, true);
  return 0;
}
