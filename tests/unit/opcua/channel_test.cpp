// The connection protocol in process (no sockets): golden bytes of HEL/ACK and ERR, the secure
// channel, the service table's access rules, a whole session reading and writing the ADS test
// table (tests/unit/ads/ads_test_support.hpp), chunked requests and responses.
#include "proto/opcua/channel.hpp"

#include <gtest/gtest.h>

#include "../ads/ads_test_support.hpp"
#include "proto/opcua/node_ids.hpp"
#include "proto/opcua/transport.hpp"

namespace virtcom::proto::opcua {
namespace {

using Bytes = std::vector<uint8_t>;

uint32_t get32(const Bytes& b, size_t at) {
  return b[at] | b[at + 1] << 8 | b[at + 2] << 16 | static_cast<uint32_t>(b[at + 3]) << 24;
}

Bytes helloBytes(uint32_t receiveBuffer = 65536) {
  Bytes b;
  Writer w(b);
  const size_t start = beginMessage(w, "HEL");
  for (uint32_t v : {0u, receiveBuffer, 65536u, 0u, 0u}) w.u32(v);
  w.string("opc.tcp://x");
  finishMessage(w, start);
  return b;
}

// The session below is anonymous: allowed to write, as `--opcua-anonymous write` does.
ServerConfig anonymousWrites() {
  ServerConfig c;
  c.anonymous = UserAccess::Write;
  return c;
}

class ChannelTest : public ::testing::Test {
 protected:
  ChannelTest() : table_(ads::testing::makeTable()), core_(table_, anonymousWrites()), channel_(core_) {}

  // Sends one message; returns what the channel answered (and whether it keeps the connection).
  Bytes send(const Bytes& frame, bool* keep = nullptr) {
    Bytes tx;
    bool k = channel_.handleFrame(frame, tx, 1'000'000'000);
    if (keep) *keep = k;
    return tx;
  }

  void open(uint32_t receiveBuffer = 65536) {
    ASSERT_EQ(send(helloBytes(receiveBuffer))[0], 'A');
    Bytes b;
    Writer w(b);
    const size_t start = beginMessage(w, "OPN");
    w.u32(0);
    w.string(kSecurityPolicyNone);
    w.nullString();
    w.nullString();
    w.u32(1);
    w.u32(1);
    encode(w, NodeId::num(0, 446));
    requestHeader(w, {});
    for (uint32_t v : {0u, 0u, 1u}) w.u32(v);  // version, issue, mode None
    w.nullString();
    w.u32(600000);
    finishMessage(w, start);
    Bytes r = send(b);
    ASSERT_EQ(std::string(r.begin(), r.begin() + 3), "OPN");
    channelId_ = r[8] | r[9] << 8;
    ASSERT_NE(channelId_, 0u);
  }

  static void requestHeader(Writer& w, const NodeId& token) {
    encode(w, token);
    encode(w, DateTime{});
    w.u32(7);  // RequestHandle
    w.u32(0);
    w.nullString();
    w.u32(0);
    encode(w, ExtensionObject{});
  }

  // A MSG with the request `typeId` and `body` (after the RequestHeader); returns the response
  // body after the response type id, with *responseType set.
  Bytes call(uint32_t typeId, const Bytes& body, uint32_t* responseType, char chunk = 'F') {
    Bytes b;
    Writer w(b);
    const size_t start = beginMessage(w, "MSG", chunk);
    w.u32(channelId_);
    w.u32(1);
    w.u32(2);
    w.u32(3);
    encode(w, NodeId::num(0, typeId));
    requestHeader(w, token_);
    w.raw(body);
    finishMessage(w, start);
    Bytes r = send(b);
    if (r.size() < 24) return {};
    Reader in(std::span<const uint8_t>(r).subspan(24));
    NodeId type;
    EXPECT_TRUE(decode(in, type));
    *responseType = type.numeric;
    return Bytes(in.rest().begin(), in.rest().end());
  }

  void createSession() {
    // CreateSession: client description, server uri, endpoint, name, nonce, certificate, timeout, max size.
    Bytes create;
    Writer c(create);
    c.nullString();
    c.nullString();
    encode(c, LocalizedText{});
    c.u32(1);
    c.nullString();
    c.nullString();
    c.i32(0);
    c.nullString();
    c.nullString();
    c.string("s");
    c.nullString();
    c.nullString();
    encode(c, 60000.0);
    c.u32(0);
    uint32_t type = 0;
    Bytes created = call(461, create, &type);
    ASSERT_EQ(type, 464u);
    Reader in(std::span<const uint8_t>(created).subspan(16 + 4 + 4));  // header with empty string table
    NodeId sessionId;
    ASSERT_TRUE(decode(in, sessionId));
    ASSERT_TRUE(decode(in, token_));
  }

  void activateSession() {
    Bytes activate;
    Writer a(activate);
    a.nullString();
    a.nullString();
    a.i32(0);
    a.i32(0);
    encode(a, ExtensionObject{NodeId::num(0, ids::kAnonymousIdentityToken), ExtensionObject::Body::Binary, std::string("\x01\x00\x00\x00x", 5)});
    a.nullString();
    a.nullString();
    uint32_t type = 0;
    Bytes activated = call(467, activate, &type);
    ASSERT_EQ(type, 470u);
    EXPECT_EQ(serviceResult(activated), 0u);
  }

  // The ServiceResult of a response body (after its type id).
  static uint32_t serviceResult(const Bytes& response) { return response.size() >= 16 ? get32(response, 12) : 0xFFFFFFFF; }

  ads::SymbolTable table_;
  ServerCore core_;
  Channel channel_;
  uint32_t channelId_ = 0;
  NodeId token_;
};

TEST_F(ChannelTest, HelloIsAnsweredWithAcknowledge) {
  Bytes ack = send(helloBytes(8192));
  // ACK F, 28 bytes: version 0, receive 65536, send min(65536, 8192), max message 4 MB, chunks 0.
  const Bytes golden{'A', 'C', 'K', 'F', 28, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0x20, 0, 0, 0, 0, 0x40, 0, 0, 0, 0, 0};
  EXPECT_EQ(ack, golden);
}

TEST_F(ChannelTest, MessagesBeforeHelloAreAnErrorAndClose) {
  bool keep = true;
  Bytes msg{'M', 'S', 'G', 'F', 8, 0, 0, 0};
  Bytes err = send(msg, &keep);
  EXPECT_FALSE(keep);
  ASSERT_GE(err.size(), 16u);
  EXPECT_EQ(std::string(err.begin(), err.begin() + 4), "ERRF");
  EXPECT_EQ(get32(err, 8), 0x807E0000u);  // BadTcpMessageTypeInvalid
}

TEST_F(ChannelTest, ServicesNeedAnActivatedSession) {
  open();
  uint32_t type = 0;
  Bytes read = call(631, {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}, &type);
  EXPECT_EQ(type, kServiceFaultId);
  EXPECT_EQ(serviceResult(read), 0x80250000u);  // BadSessionIdInvalid
  Bytes unknown = call(9999, {}, &type);
  EXPECT_EQ(type, kServiceFaultId);
  EXPECT_EQ(serviceResult(unknown), 0x800B0000u);  // BadServiceUnsupported
}

TEST_F(ChannelTest, SessionReadsAndQueuesWrites) {
  open();
  uint32_t type = 0;
  createSession();
  // Read before ActivateSession: BadSessionNotActivated.
  Bytes readBody;
  Writer r(readBody);
  encode(r, 0.0);
  r.u32(3);  // no timestamps
  r.i32(1);
  encode(r, NodeId::str(ids::kPlcNamespace, "|var|virtcom.Application.MAIN.p.y"));
  r.u32(13);
  r.nullString();
  encode(r, QualifiedName{});
  EXPECT_EQ(serviceResult(call(631, readBody, &type)), 0x80270000u);
  activateSession();
  const Bytes image = [] {
    Bytes b(64, 0);
    b[42] = 0x34;
    b[43] = 0x12;
    return b;
  }();
  core_.publish(image);
  Bytes value = call(631, readBody, &type);
  ASSERT_EQ(type, 634u);
  // Results: 1 DataValue {mask Value, Variant Int16 0x1234}, then no diagnostics.
  const Bytes tail{1, 0, 0, 0, 0x01, 0x04, 0x34, 0x12, 0, 0, 0, 0};
  ASSERT_GE(value.size(), tail.size());
  EXPECT_EQ(Bytes(value.end() - static_cast<ptrdiff_t>(tail.size()), value.end()), tail);
  // Write MAIN.count := 5 (queued for the scan) and MAIN.serial (read only): BadNotWritable.
  Bytes writeBody;
  Writer wr(writeBody);
  wr.i32(2);
  for (const char* path : {"MAIN.count", "MAIN.serial"}) {
    encode(wr, NodeId::str(ids::kPlcNamespace, std::string("|var|virtcom.Application.") + path));
    wr.u32(13);
    wr.nullString();
    DataValue v;
    v.hasValue = true;
    v.value = Variant::scalar(std::string(path) == "MAIN.count" ? Scalar(int16_t{5}) : Scalar(int32_t{5}));
    encode(wr, v);
  }
  Bytes written = call(673, writeBody, &type);
  ASSERT_EQ(type, 676u);
  const Bytes statuses{2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x3B, 0x80, 0, 0, 0, 0};
  EXPECT_EQ(Bytes(written.end() - static_cast<ptrdiff_t>(statuses.size()), written.end()), statuses);
  EXPECT_EQ(core_.pendingWrites().size(), 1u);
  EXPECT_EQ(core_.snapshot()[32], 5);
}

TEST_F(ChannelTest, ChunkedRequestsAreJoinedAndAbortedOnesDropped) {
  open();
  uint32_t type = 0;
  // An intermediate chunk of garbage, then an abort: nothing is answered, the channel stays.
  Bytes none = call(631, {1, 2, 3}, &type, 'C');
  EXPECT_TRUE(none.empty());
  Bytes b;
  Writer w(b);
  const size_t start = beginMessage(w, "MSG", 'A');
  for (uint32_t v : {channelId_, 1u, 3u, 3u}) w.u32(v);
  finishMessage(w, start);
  bool keep = false;
  EXPECT_TRUE(send(b, &keep).empty());
  EXPECT_TRUE(keep);
  // GetEndpoints after that is answered normally.
  Bytes endpoints = call(428, {0xFF, 0xFF, 0xFF, 0xFF, 0, 0, 0, 0, 0, 0, 0, 0}, &type);
  EXPECT_EQ(type, 431u);
  EXPECT_EQ(serviceResult(endpoints), 0u);
}

TEST_F(ChannelTest, LongResponsesAreCutIntoChunksOfThePeersBuffer) {
  open(8192);
  createSession();
  activateSession();
  // A Read of 600 NamespaceArray values: far beyond the client's 8 KB receive buffer.
  Bytes body;
  Writer r(body);
  encode(r, 0.0);
  r.u32(3);
  r.i32(600);
  for (int i = 0; i < 600; ++i) {
    encode(r, NodeId::num(0, ids::kNamespaceArray));
    r.u32(13);
    r.nullString();
    encode(r, QualifiedName{});
  }
  Bytes b;
  Writer w(b);
  const size_t start = beginMessage(w, "MSG");
  for (uint32_t v : {channelId_, 1u, 4u, 4u}) w.u32(v);
  encode(w, NodeId::num(0, 631));
  requestHeader(w, token_);
  w.raw(body);
  finishMessage(w, start);
  Bytes stream = send(b);
  // C chunks of at most 8192 bytes, the last one F, all of request 4.
  size_t at = 0, chunks = 0;
  char last = 0;
  while (at + 8 <= stream.size()) {
    const uint32_t size = get32(stream, at + 4);
    ASSERT_LE(size, 8192u);
    EXPECT_EQ(get32(stream, at + 20), 4u);
    last = static_cast<char>(stream[at + 3]);
    if (at + size < stream.size()) {
      EXPECT_EQ(last, 'C');
    }
    at += size;
    ++chunks;
  }
  EXPECT_EQ(at, stream.size());
  EXPECT_EQ(last, 'F');
  EXPECT_GT(chunks, 10u);
}

// Subscriptions through the channel: the first value at once, changes, keep-alives on the
// keep-alive count, Republish of the last message, and the lifetime count ending a
// subscription nobody publishes for.
class SubscriptionTest : public ChannelTest {
 protected:
  void SetUp() override {
    open();
    createSession();
    activateSession();
    Bytes body;
    Writer w(body);
    encode(w, 100.0);  // publishing interval (ms)
    w.u32(9);          // lifetime count
    w.u32(3);          // max keep-alive count
    w.u32(0);
    encode(w, true);
    w.u8(0);
    uint32_t type = 0;
    Bytes created = call(787, body, &type);
    ASSERT_EQ(type, 790u);
    subscriptionId_ = get32(created, 24);
    EXPECT_EQ(get32(created, 24 + 4 + 8), 9u);     // revised lifetime
    EXPECT_EQ(get32(created, 24 + 4 + 8 + 4), 3u);  // revised keep-alive
  }

  uint32_t monitor(const char* path, double deadband = 0) {
    Bytes body;
    Writer w(body);
    w.u32(subscriptionId_);
    w.u32(2);
    w.i32(1);
    encode(w, NodeId::str(ids::kPlcNamespace, std::string("|var|virtcom.Application.") + path));
    w.u32(13);
    w.nullString();
    encode(w, QualifiedName{});
    w.u32(2);   // Reporting
    w.u32(77);  // client handle
    encode(w, 10.0);
    if (deadband > 0) {
      Bytes filter;
      Writer f(filter);
      f.u32(1);
      f.u32(1);  // absolute
      encode(f, deadband);
      encode(w, ExtensionObject{NodeId::num(0, 724), ExtensionObject::Body::Binary, std::string(filter.begin(), filter.end())});
    } else {
      encode(w, ExtensionObject{});
    }
    w.u32(4);
    encode(w, true);
    uint32_t type = 0;
    Bytes created = call(751, body, &type);
    EXPECT_EQ(type, 754u);
    EXPECT_EQ(get32(created, 28), 0u) << statusName(get32(created, 28));
    return get32(created, 32);
  }

  // Queues a Publish (no acknowledgements): nothing is answered until tick().
  void publish() {
    uint32_t type = 0;
    EXPECT_TRUE(call(826, {0, 0, 0, 0}, &type).empty());
  }

  // The PublishResponses tick() sends at `ms` after the session began: for each, the values of
  // the Int16 notifications in it (empty: a keep-alive).
  std::vector<std::vector<int16_t>> tickAt(int64_t ms) {
    Bytes tx;
    channel_.tick(1'000'000'000 + ms * 1'000'000, tx);
    std::vector<std::vector<int16_t>> out;
    for (size_t at = 0; at + 24 <= tx.size(); at += get32(tx, at + 4)) {
      Reader r(std::span<const uint8_t>(tx).subspan(at + 24, get32(tx, at + 4) - 24));
      NodeId type;
      EXPECT_TRUE(decode(r, type));
      EXPECT_EQ(type.numeric, 829u);
      std::span<const uint8_t> skip;
      uint32_t sub = 0, available = 0, sequence = 0, notifications = 0;
      // ResponseHeader (24 bytes with empty parts), subscription id, available numbers.
      EXPECT_TRUE(r.bytes(24, skip) && r.u32(sub) && r.u32(available));
      EXPECT_EQ(sub, subscriptionId_);
      EXPECT_TRUE(r.bytes(4 * available + 1, skip) && r.u32(sequence) && r.bytes(8, skip) && r.u32(notifications));
      std::vector<int16_t> values;
      if (notifications == 1) {
        ExtensionObject change;
        EXPECT_TRUE(decode(r, change));
        EXPECT_EQ(change.typeId, NodeId::num(0, 811));
        Reader c(change.view());
        uint32_t count = 0;
        EXPECT_TRUE(c.u32(count));
        for (uint32_t i = 0; i < count; ++i) {
          uint32_t handle = 0;
          DataValue dv;
          EXPECT_TRUE(c.u32(handle) && decode(c, dv));
          EXPECT_EQ(handle, 77u);
          values.push_back(std::get<int16_t>(dv.value.values.at(0)));
        }
      }
      out.push_back(values);
    }
    return out;
  }

  void setCount(int16_t v) {
    Bytes image(64, 0);
    image[32] = static_cast<uint8_t>(v);
    image[33] = static_cast<uint8_t>(static_cast<uint16_t>(v) >> 8);
    core_.publish(image);
  }

  uint32_t subscriptionId_ = 0;
};

TEST_F(SubscriptionTest, ChangesArriveAndKeepAlivesFillTheSilence) {
  setCount(5);
  monitor("MAIN.count");
  EXPECT_TRUE(tickAt(50).empty());  // before the first publishing interval
  publish();
  EXPECT_EQ(tickAt(100), (std::vector<std::vector<int16_t>>{{5}}));  // the first value at once
  setCount(6);
  setCount(7);
  publish();
  EXPECT_TRUE(tickAt(150).empty());  // no request without the interval
  EXPECT_EQ(tickAt(200), (std::vector<std::vector<int16_t>>{{7}}));  // sampled at 200: the latest
  publish();
  EXPECT_TRUE(tickAt(300).empty());
  EXPECT_TRUE(tickAt(400).empty());
  EXPECT_EQ(tickAt(500), (std::vector<std::vector<int16_t>>{{}}));  // third silent interval: keep-alive
}

TEST_F(SubscriptionTest, DeadbandHoldsBackSmallChanges) {
  setCount(100);
  monitor("MAIN.count", 10);
  publish();
  EXPECT_EQ(tickAt(100), (std::vector<std::vector<int16_t>>{{100}}));
  setCount(105);
  publish();
  tickAt(200);
  setCount(111);
  EXPECT_EQ(tickAt(300), (std::vector<std::vector<int16_t>>{{111}}));  // 105 held back (the 200 answer was a keep-alive or nothing)
}

TEST_F(SubscriptionTest, RepublishAndLifetime) {
  setCount(1);
  monitor("MAIN.count");
  publish();
  ASSERT_EQ(tickAt(100).size(), 1u);
  uint32_t type = 0;
  Bytes again = call(832, {static_cast<uint8_t>(subscriptionId_), 0, 0, 0, 1, 0, 0, 0}, &type);
  EXPECT_EQ(type, 835u);
  EXPECT_EQ(get32(again, 24), 1u);  // the NotificationMessage's sequence number
  Bytes missing = call(832, {static_cast<uint8_t>(subscriptionId_), 0, 0, 0, 9, 0, 0, 0}, &type);
  EXPECT_EQ(type, kServiceFaultId);
  // No Publish request for the lifetime count (9 intervals): the subscription is gone.
  for (int64_t ms = 200; ms <= 2000; ms += 100) tickAt(ms);
  Bytes gone = call(826, {0, 0, 0, 0}, &type);
  EXPECT_EQ(type, kServiceFaultId);
  EXPECT_EQ(serviceResult(gone), 0x80790000u);  // BadNoSubscription
}

}  // namespace
}  // namespace virtcom::proto::opcua
