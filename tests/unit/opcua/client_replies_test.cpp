// The client bridge against replies no well-behaved server sends, served by a CannedServer
// (tests/support): the connection's first replies as `virtcom exec --opcua` sent them (the fuzz
// seed corpus/opcua_client/virtcom_session), then a Read response written here. Each test is an
// input the fuzz target (tests/fuzz/fuzz_opcua_client.cpp) found mishandled.
#include <gtest/gtest.h>

#include <functional>

#include "proto/opcua/client_bridge.hpp"
#include "proto/opcua/transport.hpp"
#include "support/canned_server.hpp"
#include "support/read_file.hpp"

namespace virtcom::proto::opcua {
namespace {

constexpr uint32_t kReadResponseId = 634;
constexpr uint32_t kStartReadRequestId = 4;  // after OpenSecureChannel, CreateSession, ActivateSession

// ACK, the OpenSecureChannel, CreateSession and ActivateSession responses of a real session.
std::vector<uint8_t> sessionOpened() {
  const std::string seed = test::readFile(std::string(VIRTCOM_SOURCE_DIR) + "/tests/fuzz/corpus/opcua_client/virtcom_session");
  std::vector<uint8_t> stream(seed.begin(), seed.end());
  size_t at = 0;
  for (int message = 0; message < 4; ++message) {
    FrameScan scan = scanFrame(std::span<const uint8_t>(stream).subspan(at), 1 << 20);
    EXPECT_EQ(scan.status, FrameStatus::Complete);
    at += scan.size;
  }
  stream.resize(at);
  return stream;
}

// A Read response to `requestId` whose results `results` writes (their count included).
void appendReadResponse(std::vector<uint8_t>& stream, uint32_t requestId, const std::function<void(Writer&)>& results) {
  Writer w(stream);
  const size_t start = beginMessage(w, "MSG");
  w.u32(1);  // SecureChannelId, TokenId, SequenceNumber: not checked by the client
  w.u32(1);
  w.u32(100);
  w.u32(requestId);
  encode(w, NodeId::num(0, kReadResponseId));
  encode(w, DateTime{});  // ResponseHeader: Timestamp, RequestHandle, ServiceResult, diagnostics, StringTable, AdditionalHeader
  w.u32(0);
  w.u32(0);
  w.u8(0);
  w.i32(-1);
  encode(w, ExtensionObject{});
  results(w);
  w.i32(-1);  // DiagnosticInfos
  finishMessage(w, start);
}

class OpcuaClientReplies : public ::testing::Test {
 protected:
  // Starts a bridge of one Boolean device output written to the PLC against `stream`.
  std::unique_ptr<ClientBridge> start(const std::vector<uint8_t>& stream, ClientBridge::StartReport& report) {
    server_ = std::make_unique<test::CannedServer>(stream);
    BridgeConfig c;
    c.client.server = {0x7f000001, server_->port()};
    c.client.endpointUrl = "opc.tcp://127.0.0.1:" + std::to_string(server_->port());
    c.signals = {{"ns=4;s=MAIN.done", "MAIN.done", "Clamp.done", bus_.add("Clamp.done", ElemType::Bool), true, false}};
    return ClientBridge::start(std::move(c), bus_, report);
  }

  TagBus bus_;
  std::unique_ptr<test::CannedServer> server_;
};

// Regression: an array of Byte as the UserAccessLevel was taken for a Byte, its first element
// read from the empty bytes of the array (a null pointer).
TEST_F(OpcuaClientReplies, AUserAccessLevelThatIsAnArrayIsAMalformedReply) {
  std::vector<uint8_t> stream = sessionOpened();
  appendReadResponse(stream, kStartReadRequestId, [](Writer& w) {
    w.i32(2);
    w.u8(kDataValueValue);  // the Value: a Boolean
    w.u8(static_cast<uint8_t>(BuiltinType::Boolean));
    w.u8(1);
    w.u8(kDataValueValue);  // the UserAccessLevel: an array of one Byte
    w.u8(static_cast<uint8_t>(BuiltinType::Byte) | kVariantArray);
    w.i32(1);
    w.u8(0x03);
  });
  ClientBridge::StartReport report;
  EXPECT_EQ(start(stream, report), nullptr);
  ASSERT_EQ(report.problems.size(), 1u);
  EXPECT_EQ(report.problems[0].text, "opcua: the OPC UA server at opc.tcp://127.0.0.1:" + std::to_string(server_->port()) +
                                         " sent the UserAccessLevel of 'ns=4;s=MAIN.done' as an array of Byte, not a Byte");
}

TEST_F(OpcuaClientReplies, AWritableBooleanStartsTheBridge) {
  std::vector<uint8_t> stream = sessionOpened();
  appendReadResponse(stream, kStartReadRequestId, [](Writer& w) {
    w.i32(2);
    w.u8(kDataValueValue);
    w.u8(static_cast<uint8_t>(BuiltinType::Boolean));
    w.u8(0);
    w.u8(kDataValueValue);
    w.u8(static_cast<uint8_t>(BuiltinType::Byte));
    w.u8(0x03);  // CurrentRead | CurrentWrite
  });
  ClientBridge::StartReport report;
  EXPECT_NE(start(stream, report), nullptr);
  EXPECT_TRUE(report.problems.empty());
}

}  // namespace
}  // namespace virtcom::proto::opcua
