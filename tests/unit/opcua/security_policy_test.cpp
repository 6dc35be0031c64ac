// Basic256Sha256's message security: P_SHA256 against the published TLS 1.2 PRF vector, the
// key layout, the padding rule, and symmetric chunks against vectors computed independently
// (Python's hmac and the cryptography package's AES-256-CBC) and round trips; asymmetric
// (OpenSecureChannel) chunks between two generated certificates.
#include "proto/opcua/security_policy.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "proto/opcua/pki.hpp"
#include "hex_bytes.hpp"

namespace virtcom::proto::opcua {
namespace {

using testing::hex;
using testing::unhex;

TEST(SecurityPolicy, PSha256MatchesThePublishedTls12PrfVector) {
  // The TLS 1.2 PRF (SHA-256) test vector circulated on the IETF TLS list: P_SHA256(secret,
  // "test label" + seed), the first 100 bytes.
  const auto secret = unhex("9B BE 43 6B A9 40 F0 17 B1 76 52 84 9A 71 DB 35");
  std::vector<uint8_t> seed{'t', 'e', 's', 't', ' ', 'l', 'a', 'b', 'e', 'l'};
  for (uint8_t b : unhex("A0 BA 9F 93 6C DA 31 18 27 A6 F7 96 FF D5 19 8C")) seed.push_back(b);
  std::vector<uint8_t> out(100);
  ASSERT_TRUE(pSha256(secret, seed, out));
  EXPECT_EQ(hex(out),
            "E3 F2 29 BA 72 7B E1 7B 8D 12 26 20 55 7C D4 53 C2 AA B2 1D 07 C3 D4 95 32 9B 52 D4 E6 1E DB 5A 6B 30 17 91 E9 0D 35 "
            "C9 C9 A4 6B 4E 14 BA F9 AF 0F A0 22 F7 07 7D EF 17 AB FD 37 97 C0 56 4B AB 4F BC 91 66 6E 9D EF 9B 97 FC E3 4F 79 67 "
            "89 BA A4 80 82 D1 22 EE 42 C5 A7 2E 5A 51 10 FF F7 01 87 34 7B 66");
}

TEST(SecurityPolicy, KeysAreSigningThenEncryptingThenIv) {
  const std::vector<uint8_t> secret(32, 0xAA), seed(32, 0x55);
  std::vector<uint8_t> stream(80);
  ASSERT_TRUE(pSha256(secret, seed, stream));
  SymmetricKeys k;
  ASSERT_TRUE(deriveKeys(secret, seed, k));
  EXPECT_TRUE(std::equal(k.signing.begin(), k.signing.end(), stream.begin()));
  EXPECT_TRUE(std::equal(k.encrypting.begin(), k.encrypting.end(), stream.begin() + 32));
  EXPECT_TRUE(std::equal(k.iv.begin(), k.iv.end(), stream.begin() + 64));
  SymmetricKeys other;
  ASSERT_TRUE(deriveKeys(seed, secret, other));
  EXPECT_NE(other.signing, k.signing) << "the two directions have different keys";
}

TEST(SecurityPolicy, PaddingFillsWholeBlocks) {
  EXPECT_EQ(paddingFor(13, 16, 32), 2u);  // 13 + 1 + 2 + 32 = 48
  EXPECT_EQ(paddingFor(15, 16, 32), 0u);  // 15 + 1 + 32 = 48
  EXPECT_EQ(paddingFor(16, 16, 32), 15u);
  for (size_t n = 0; n < 600; ++n) EXPECT_EQ((n + 1 + paddingFor(n, 214, 256) + 256) % 214, 0u) << n;
}

SymmetricKeys fixedKeys() {
  SymmetricKeys k;
  k.signing.fill(0x11);
  k.encrypting.fill(0x22);
  k.iv.fill(0x33);
  return k;
}

// MSG F, channel 1, token 2, sequence 3, request 4, body "hello"; the size patched by sealing.
std::vector<uint8_t> helloChunk() { return unhex("4D 53 47 46 00 00 00 00 01 00 00 00 02 00 00 00 03 00 00 00 04 00 00 00 68 65 6C 6C 6F"); }

TEST(SecurityPolicy, SignedChunkMatchesTheIndependentVector) {
  auto tx = helloChunk();
  ASSERT_TRUE(sealSymmetric(tx, 0, SecurityMode::Sign, fixedKeys()));
  EXPECT_EQ(hex(tx),
            "4D 53 47 46 3D 00 00 00 01 00 00 00 02 00 00 00 03 00 00 00 04 00 00 00 68 65 6C 6C 6F 6A 7C 0C 55 C8 DA 6E B9 5F 9B "
            "43 C3 82 38 62 B7 40 17 FA 84 E5 C8 EC 12 13 AC 99 9E F5 E0 D6 97");
}

TEST(SecurityPolicy, EncryptedChunkMatchesTheIndependentVector) {
  auto tx = helloChunk();
  ASSERT_TRUE(sealSymmetric(tx, 0, SecurityMode::SignAndEncrypt, fixedKeys()));
  EXPECT_EQ(hex(tx),
            "4D 53 47 46 40 00 00 00 01 00 00 00 02 00 00 00 A0 3D 77 BB 01 17 5D 82 5B DC 1B D6 D5 2B E9 2D 9E 5D 81 BD B3 46 B3 "
            "87 49 25 FD 01 F8 B6 EC 44 00 8D 9D C2 29 94 AD 60 94 D7 68 C4 E3 35 AA C5");
}

TEST(SecurityPolicy, SymmetricChunksOpenBackAndRefuseTampering) {
  for (SecurityMode mode : {SecurityMode::Sign, SecurityMode::SignAndEncrypt}) {
    std::vector<uint8_t> tx{0xEE};  // a chunk after other bytes
    const auto chunk = helloChunk();
    tx.insert(tx.end(), chunk.begin(), chunk.end());
    ASSERT_TRUE(sealSymmetric(tx, 1, mode, fixedKeys()));
    std::vector<uint8_t> received(tx.begin() + 1, tx.end());
    std::span<const uint8_t> plain;
    ASSERT_TRUE(openSymmetric(received, mode, fixedKeys(), plain));
    EXPECT_EQ(hex({plain.begin(), plain.end()}), "03 00 00 00 04 00 00 00 68 65 6C 6C 6F");
    std::vector<uint8_t> tampered(tx.begin() + 1, tx.end());
    tampered[20] ^= 1;
    EXPECT_FALSE(openSymmetric(tampered, mode, fixedKeys(), plain));
    std::vector<uint8_t> otherKeys(tx.begin() + 1, tx.end());
    SymmetricKeys wrong = fixedKeys();
    wrong.signing[0] = 0;
    EXPECT_FALSE(openSymmetric(otherKeys, mode, wrong, plain));
  }
}

class AsymmetricTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = std::filesystem::temp_directory_path() / ("virtcom-asym-" + std::to_string(::getpid()));
    auto server = openPki((root_ / "server").string(), "urn:test:server");
    auto client = openPki((root_ / "client").string(), "urn:test:client");
    ASSERT_TRUE(server) << server.error();
    ASSERT_TRUE(client) << client.error();
    server_ = {server->certificate, server->keyPem, client->certificate};
    client_ = {client->certificate, client->keyPem, server->certificate};
  }
  void TearDown() override { std::filesystem::remove_all(root_); }
  std::filesystem::path root_;
  AsymmetricKeys server_, client_;
};

TEST_F(AsymmetricTest, OpenSecureChannelChunksOpenWithTheOtherSidesKeys) {
  // OPN F, a header of 12 bytes standing for the asymmetric security header, then the sequence
  // header and a body of 300 bytes (two RSA-OAEP blocks with the padding and signature).
  std::vector<uint8_t> tx = unhex("4F 50 4E 46 00 00 00 00 01 02 03 04 05 06 07 08 09 0A 0B 0C 05 00 00 00 06 00 00 00");
  for (int i = 0; i < 300; ++i) tx.push_back(static_cast<uint8_t>(i));
  const std::vector<uint8_t> sent(tx.begin() + 20, tx.end());
  ASSERT_TRUE(sealAsymmetric(tx, 0, 20, client_));
  EXPECT_EQ((tx.size() - 20) % 256, 0u) << "whole 256-byte RSA blocks";
  EXPECT_EQ(tx[4] | tx[5] << 8, static_cast<int>(tx.size()));
  std::vector<uint8_t> scratch;
  std::span<const uint8_t> plain;
  ASSERT_TRUE(openAsymmetric(tx, 20, server_, scratch, plain));
  EXPECT_EQ(std::vector<uint8_t>(plain.begin(), plain.end()), sent);
  EXPECT_FALSE(openAsymmetric(tx, 20, client_, scratch, plain)) << "only the receiver's key decrypts";
  tx[10] ^= 1;  // the clear header is signed too
  EXPECT_FALSE(openAsymmetric(tx, 20, server_, scratch, plain));
}

}  // namespace
}  // namespace virtcom::proto::opcua
