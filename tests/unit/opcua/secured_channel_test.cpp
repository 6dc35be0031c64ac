// The server's side of Basic256Sha256 in process (no sockets): a client written here with the
// same sealing functions (security_policy.hpp) opens a SignAndEncrypt channel and calls a service,
// then breaks one rule at a time; each break is refused with its status (an ERR message, the
// connection closed). node-opcua drives the good path end to end (tests/e2e/opcua_e2e_test.cpp,
// SecuredEndpointsAndTheTrustListWithNodeOpcua).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "../ads/ads_test_support.hpp"
#include "proto/opcua/channel.hpp"
#include "proto/opcua/crypto.hpp"
#include "proto/opcua/transport.hpp"

namespace virtcom::proto::opcua {
namespace {

using Bytes = std::vector<uint8_t>;

constexpr uint32_t kBadSecurityChecksFailed = 0x80130000, kBadSequenceNumberInvalid = 0x80880000,
                   kBadSecureChannelIdInvalid = 0x80220000;

std::string text(const Bytes& b) { return std::string(b.begin(), b.end()); }
uint32_t get32(std::span<const uint8_t> b, size_t at) {
  return b[at] | b[at + 1] << 8 | b[at + 2] << 16 | static_cast<uint32_t>(b[at + 3]) << 24;
}

class SecuredChannelTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(loadCrypto());
    root_ = std::filesystem::temp_directory_path() / ("virtcom-secured-" + std::to_string(::getpid()));
    auto server = openPki((root_ / "server").string(), "urn:virtcom:plc");
    auto client = openPki((root_ / "client").string(), "urn:test:client");
    ASSERT_TRUE(server) << server.error();
    ASSERT_TRUE(client) << client.error();
    serverPki_ = *server;
    client_ = {client->certificate, client->keyPem, server->certificate};
    trustClient(true);
  }
  void TearDown() override { std::filesystem::remove_all(root_); }

  void trustClient(bool any) {
    Pki pki = serverPki_;
    pki.trustAny = any;
    ServerConfig config;
    config.securityModes = {SecurityMode::None, SecurityMode::Sign, SecurityMode::SignAndEncrypt};
    config.pki = std::make_shared<const Pki>(pki);
    channel_.reset();
    core_ = std::make_unique<ServerCore>(table_, config);
    channel_ = std::make_unique<Channel>(*core_);
  }

  Bytes send(const Bytes& frame, bool* keep = nullptr) {
    Bytes tx;
    const bool k = channel_->handleFrame(frame, tx, 1'000'000'000);
    if (keep) *keep = k;
    return tx;
  }

  static void requestHeader(Writer& w) {
    encode(w, NodeId{});
    encode(w, DateTime{});
    w.u32(7);
    w.u32(0);
    w.nullString();
    w.u32(0);
    encode(w, ExtensionObject{});
  }

  // HEL, then a secured OPN issuing a channel of `mode` with `thumbprint` as the receiver's,
  // its byte `flipFromEnd` from the end changed after sealing if not 0; returns the server's answer.
  Bytes openSecured(SecurityMode mode, std::span<const uint8_t> thumbprint, size_t flipFromEnd = 0) {
    EXPECT_EQ(send(hello())[0], 'A');
    clientNonce_.assign(kSecureNonceBytes, 0x5A);
    Bytes b;
    Writer w(b);
    const size_t start = beginMessage(w, "OPN");
    w.u32(0);
    w.string(kSecurityPolicyBasic256Sha256);
    encode(w, ByteString{std::string(client_.ownCertificate.begin(), client_.ownCertificate.end())});
    encode(w, ByteString{std::string(thumbprint.begin(), thumbprint.end())});
    const size_t headerEnd = b.size();
    w.u32(1);  // sequence number
    w.u32(1);  // request id
    encode(w, NodeId::num(0, 446));
    requestHeader(w);
    for (uint32_t v : {0u, 0u, static_cast<uint32_t>(mode)}) w.u32(v);  // version, issue, mode
    encode(w, ByteString{std::string(clientNonce_.begin(), clientNonce_.end())});
    w.u32(600000);
    finishMessage(w, start);
    EXPECT_TRUE(sealAsymmetric(b, start, headerEnd, client_));
    if (flipFromEnd != 0) b[b.size() - flipFromEnd] ^= 0x01;
    return send(b);
  }

  // Opens a channel of `mode` and derives both sides' keys from the nonces.
  void open(SecurityMode mode) {
    mode_ = mode;
    const Bytes answer = openSecured(mode, serverPki_.thumbprint);
    ASSERT_EQ(text(answer).substr(0, 3), "OPN") << text(answer);
    Reader header(std::span<const uint8_t>(answer).subspan(12));
    std::string policy;
    ByteString certificate, thumbprint;
    ASSERT_TRUE(decode(header, policy) && decode(header, certificate) && decode(header, thumbprint));
    const size_t headerEnd = answer.size() - header.rest().size();
    std::vector<uint8_t> scratch;
    std::span<const uint8_t> plain;
    ASSERT_TRUE(openAsymmetric(answer, headerEnd, client_, scratch, plain)) << "signed by the server, encrypted for the client";
    Reader in(plain.subspan(8));  // the sequence header
    NodeId type;
    ASSERT_TRUE(decode(in, type));
    ASSERT_EQ(type.numeric, 449u);
    Reader token(in.rest().subspan(24 + 4));  // the response header, the server's protocol version
    uint32_t lifetime = 0;
    uint64_t created = 0;
    ByteString serverNonce;
    ASSERT_TRUE(token.u32(channelId_) && token.u32(tokenId_) && token.u64(created) && token.u32(lifetime) && decode(token, serverNonce));
    ASSERT_EQ(serverNonce.bytes.size(), kSecureNonceBytes);
    const auto server = serverNonce.view();
    ASSERT_TRUE(deriveKeys(server, clientNonce_, clientKeys_));
    ASSERT_TRUE(deriveKeys(clientNonce_, server, serverKeys_));
  }

  // A GetEndpoints request as a MSG chunk sealed with `mode` and the client's keys.
  Bytes getEndpoints(uint32_t sequence, SecurityMode mode) {
    Bytes b;
    Writer w(b);
    const size_t start = beginMessage(w, "MSG");
    w.u32(channelId_);
    w.u32(tokenId_);
    w.u32(sequence);
    w.u32(sequence);  // request id
    encode(w, NodeId::num(0, 428));
    requestHeader(w);
    w.nullString();  // EndpointUrl
    w.i32(0);        // LocaleIds
    w.i32(0);        // ProfileUris
    finishMessage(w, start);
    EXPECT_TRUE(sealSymmetric(b, start, mode, clientKeys_));
    return b;
  }

  // The type id of the response in a MSG from the server, opened with its keys; 0 if none.
  uint32_t responseType(Bytes answer) {
    std::span<const uint8_t> plain;
    if (text(answer).substr(0, 3) != "MSG" || !openSymmetric(answer, mode_, serverKeys_, plain)) return 0;
    Reader in(plain.subspan(8));
    NodeId type;
    return decode(in, type) ? type.numeric : 0;
  }

  // The status of an ERR message; 0 if it is none.
  static uint32_t errorStatus(const Bytes& answer) { return text(answer).substr(0, 3) == "ERR" ? get32(answer, 8) : 0; }

  static Bytes hello() {
    Bytes b;
    Writer w(b);
    const size_t start = beginMessage(w, "HEL");
    for (uint32_t v : {0u, 65536u, 65536u, 0u, 0u}) w.u32(v);
    w.string("opc.tcp://x");
    finishMessage(w, start);
    return b;
  }

  std::filesystem::path root_;
  Pki serverPki_;
  AsymmetricKeys client_;
  ads::SymbolTable table_ = ads::testing::makeTable();
  std::unique_ptr<ServerCore> core_;
  std::unique_ptr<Channel> channel_;
  std::vector<uint8_t> clientNonce_;
  SymmetricKeys clientKeys_, serverKeys_;
  SecurityMode mode_ = SecurityMode::None;
  uint32_t channelId_ = 0, tokenId_ = 0;
};

TEST_F(SecuredChannelTest, SignAndEncryptServesAndSignServes) {
  open(SecurityMode::SignAndEncrypt);
  EXPECT_EQ(responseType(send(getEndpoints(2, SecurityMode::SignAndEncrypt))), 431u);
  EXPECT_EQ(responseType(send(getEndpoints(3, SecurityMode::SignAndEncrypt))), 431u);
  trustClient(true);
  open(SecurityMode::Sign);
  EXPECT_EQ(responseType(send(getEndpoints(2, SecurityMode::Sign))), 431u);
}

TEST_F(SecuredChannelTest, AChunkWithOneByteChangedIsRefused) {
  for (size_t at : {size_t{30}, size_t{60}}) {  // in the encrypted body; the signature
    trustClient(true);
    open(SecurityMode::SignAndEncrypt);
    Bytes chunk = getEndpoints(2, SecurityMode::SignAndEncrypt);
    chunk[chunk.size() - at] ^= 0x01;
    bool keep = true;
    EXPECT_EQ(errorStatus(send(chunk, &keep)), kBadSecurityChecksFailed) << at;
    EXPECT_FALSE(keep);
  }
}

TEST_F(SecuredChannelTest, ASignedChunkOnAnEncryptedChannelIsRefused) {
  open(SecurityMode::SignAndEncrypt);
  EXPECT_EQ(errorStatus(send(getEndpoints(2, SecurityMode::Sign))), kBadSecurityChecksFailed);
}

TEST_F(SecuredChannelTest, SequenceNumbersMustRiseByOne) {
  open(SecurityMode::SignAndEncrypt);
  EXPECT_EQ(responseType(send(getEndpoints(2, SecurityMode::SignAndEncrypt))), 431u);
  EXPECT_EQ(errorStatus(send(getEndpoints(2, SecurityMode::SignAndEncrypt))), kBadSequenceNumberInvalid) << "a replayed chunk";
  trustClient(true);
  open(SecurityMode::SignAndEncrypt);
  EXPECT_EQ(errorStatus(send(getEndpoints(4, SecurityMode::SignAndEncrypt))), kBadSequenceNumberInvalid) << "a chunk skipped";
}

TEST_F(SecuredChannelTest, AChunkUnderAnUnknownTokenIsRefused) {
  open(SecurityMode::SignAndEncrypt);
  ++tokenId_;
  bool keep = true;
  EXPECT_EQ(errorStatus(send(getEndpoints(2, SecurityMode::SignAndEncrypt), &keep)), kBadSecureChannelIdInvalid);
  EXPECT_FALSE(keep);
}

TEST_F(SecuredChannelTest, AnOpenRequestWithOneByteChangedIsRefused) {
  EXPECT_EQ(errorStatus(openSecured(SecurityMode::SignAndEncrypt, serverPki_.thumbprint, 1)), kBadSecurityChecksFailed);
}

TEST_F(SecuredChannelTest, AnotherReceiverThumbprintIsRefused) {
  std::array<uint8_t, 20> other = serverPki_.thumbprint;
  other[0] ^= 0xFF;
  EXPECT_EQ(errorStatus(openSecured(SecurityMode::SignAndEncrypt, other)), kBadSecurityChecksFailed);
}

TEST_F(SecuredChannelTest, AnUntrustedClientIsRefusedAndItsCertificateKeptForTheOperator) {
  trustClient(false);
  EXPECT_EQ(errorStatus(openSecured(SecurityMode::SignAndEncrypt, serverPki_.thumbprint)), kBadSecurityChecksFailed);
  EXPECT_NE(channel_->rejection().find("the client certificate is not trusted; to trust it, move "), std::string::npos)
      << channel_->rejection();
  size_t rejected = 0;
  for (const auto& entry : std::filesystem::directory_iterator(root_ / "server/rejected/certs")) {
    ++rejected;
    std::filesystem::rename(entry.path(), root_ / "server/trusted/certs" / entry.path().filename());
  }
  EXPECT_EQ(rejected, 1u);
  // Moved to trusted/certs: the same client is let in.
  trustClient(false);
  open(SecurityMode::SignAndEncrypt);
  EXPECT_EQ(responseType(send(getEndpoints(2, SecurityMode::SignAndEncrypt))), 431u);
}

}  // namespace
}  // namespace virtcom::proto::opcua
