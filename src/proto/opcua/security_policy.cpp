#include "proto/opcua/security_policy.hpp"

#include <algorithm>

#include "proto/opcua/crypto.hpp"

namespace virtcom::proto::opcua {

namespace {

constexpr size_t kSha256Bytes = 32;
// RSA-OAEP with SHA-1 takes 2 * 20 + 2 bytes of every block (RFC 8017 §7.1.1).
constexpr size_t kOaepSha1Overhead = 42;
// Beyond 2048-bit keys the padding may exceed 255 bytes: an ExtraPaddingSize byte carries its
// high byte (OPC 10000-6 §6.7.2.5).
constexpr size_t kExtraPaddingKeyBytes = 256;

void putSize(std::vector<uint8_t>& tx, size_t start) {
  const auto size = static_cast<uint32_t>(tx.size() - start);
  for (int i = 0; i < 4; ++i) tx[start + 4 + i] = static_cast<uint8_t>(size >> (8 * i));
}

// Appends PaddingSize, the padding and (for keys over 2048 bits) ExtraPaddingSize.
void appendPadding(std::vector<uint8_t>& tx, size_t padding, bool extra) {
  const auto low = static_cast<uint8_t>(padding);
  tx.insert(tx.end(), padding + 1, low);
  if (extra) tx.push_back(static_cast<uint8_t>(padding >> 8));
}

// The padding length a plaintext ending at `end` (the signature cut off) says it has, checked
// byte by byte; SIZE_MAX if wrong. `extra`: an ExtraPaddingSize byte ends it.
size_t paddingOf(std::span<const uint8_t> plain, bool extra) {
  if (plain.size() < (extra ? 2u : 1u)) return SIZE_MAX;
  const size_t high = extra ? plain.back() : 0;
  if (extra) plain = plain.first(plain.size() - 1);
  const uint8_t low = plain.back();
  const size_t padding = high << 8 | low;
  if (padding + 1 > plain.size()) return SIZE_MAX;
  for (size_t i = plain.size() - padding - 1; i < plain.size(); ++i)
    if (plain[i] != low) return SIZE_MAX;
  return padding + 1 + (extra ? 1 : 0);
}

}  // namespace

bool pSha256(std::span<const uint8_t> secret, std::span<const uint8_t> seed, std::span<uint8_t> out) {
  const CryptoCalls& c = crypto();
  // A(1) = HMAC(secret, seed), A(i) = HMAC(secret, A(i-1)); each block is HMAC(secret, A(i) + seed).
  std::vector<uint8_t> input(kSha256Bytes + seed.size());
  std::copy(seed.begin(), seed.end(), input.begin() + kSha256Bytes);
  uint8_t a[kSha256Bytes], block[kSha256Bytes];
  if (!c.hmacSha256(secret.data(), secret.size(), seed.data(), seed.size(), a)) return false;
  for (size_t done = 0; done < out.size(); done += kSha256Bytes) {
    std::copy(a, a + kSha256Bytes, input.begin());
    if (!c.hmacSha256(secret.data(), secret.size(), input.data(), input.size(), block) ||
        !c.hmacSha256(secret.data(), secret.size(), a, kSha256Bytes, a))
      return false;
    std::copy_n(block, std::min(kSha256Bytes, out.size() - done), out.begin() + done);
  }
  return true;
}

bool deriveKeys(std::span<const uint8_t> secret, std::span<const uint8_t> seed, SymmetricKeys& out) {
  std::array<uint8_t, 80> bytes{};
  if (!pSha256(secret, seed, bytes)) return false;
  std::copy_n(bytes.begin(), 32, out.signing.begin());
  std::copy_n(bytes.begin() + 32, 32, out.encrypting.begin());
  std::copy_n(bytes.begin() + 64, 16, out.iv.begin());
  return true;
}

size_t paddingFor(size_t length, size_t blockBytes, size_t signatureBytes) {
  return (blockBytes - (length + 1 + signatureBytes) % blockBytes) % blockBytes;
}

size_t symmetricChunkRoom(size_t bufferBytes, SecurityMode mode) {
  constexpr size_t kHeaders = kSymmetricClearBytes + 8;  // and the sequence header
  if (mode == SecurityMode::None) return bufferBytes - kHeaders;
  if (mode == SecurityMode::Sign) return bufferBytes - kHeaders - kSymmetricSignatureBytes;
  return (bufferBytes - kSymmetricClearBytes) / kAesBlockBytes * kAesBlockBytes - kSymmetricSignatureBytes - 1 - 8;
}

bool sequenceNumberFollows(uint32_t last, uint32_t next) {
  constexpr uint32_t kWrapFrom = 0xFFFFFFFFu - 1024, kWrapBelow = 1024;
  return next == last + 1 || (last > kWrapFrom && next < kWrapBelow);
}

bool sealSymmetric(std::vector<uint8_t>& tx, size_t start, SecurityMode mode, const SymmetricKeys& keys) {
  const bool encrypt = mode == SecurityMode::SignAndEncrypt;
  if (encrypt) appendPadding(tx, paddingFor(tx.size() - start - kSymmetricClearBytes, kAesBlockBytes, kSymmetricSignatureBytes), false);
  tx.resize(tx.size() + kSymmetricSignatureBytes);
  putSize(tx, start);
  const size_t signedEnd = tx.size() - kSymmetricSignatureBytes;
  const CryptoCalls& c = crypto();
  if (!c.hmacSha256(keys.signing.data(), keys.signing.size(), tx.data() + start, signedEnd - start, tx.data() + signedEnd))
    return false;
  if (!encrypt) return true;
  uint8_t* plain = tx.data() + start + kSymmetricClearBytes;
  return c.aes256Cbc(true, keys.encrypting.data(), keys.iv.data(), plain, tx.size() - start - kSymmetricClearBytes, plain);
}

bool openSymmetric(std::span<uint8_t> chunk, SecurityMode mode, const SymmetricKeys& keys, std::span<const uint8_t>& plain) {
  const bool encrypted = mode == SecurityMode::SignAndEncrypt;
  if (chunk.size() < kSymmetricClearBytes + kSymmetricSignatureBytes) return false;
  const CryptoCalls& c = crypto();
  auto secret = chunk.subspan(kSymmetricClearBytes);
  if (encrypted && (secret.size() % kAesBlockBytes != 0 ||
                    !c.aes256Cbc(false, keys.encrypting.data(), keys.iv.data(), secret.data(), secret.size(), secret.data())))
    return false;
  const size_t signedEnd = chunk.size() - kSymmetricSignatureBytes;
  uint8_t mac[kSymmetricSignatureBytes];
  if (!c.hmacSha256(keys.signing.data(), keys.signing.size(), chunk.data(), signedEnd, mac) ||
      !c.equalInConstantTime(mac, chunk.data() + signedEnd, kSymmetricSignatureBytes))
    return false;
  auto body = chunk.subspan(kSymmetricClearBytes, signedEnd - kSymmetricClearBytes);
  const size_t padding = encrypted ? paddingOf(body, false) : 0;
  if (padding == SIZE_MAX) return false;
  plain = body.first(body.size() - padding);
  return true;
}

size_t rsaKeyBytes(std::span<const uint8_t> certificate) {
  int64_t notBefore = 0, notAfter = 0;
  char uri[kMaxCertificateUri];
  size_t uriLength = 0;
  uint32_t bits = 0;
  if (!crypto().certificateFacts(certificate.data(), certificate.size(), &notBefore, &notAfter, uri, sizeof uri, &uriLength, &bits))
    return 0;
  return bits / 8;
}

bool sealAsymmetric(std::vector<uint8_t>& tx, size_t start, size_t headerEnd, const AsymmetricKeys& keys) {
  const size_t peerBytes = rsaKeyBytes(keys.peerCertificate), ownBytes = rsaKeyBytes(keys.ownCertificate);
  if (peerBytes <= kOaepSha1Overhead || ownBytes == 0) return false;
  const size_t plainBlock = peerBytes - kOaepSha1Overhead;
  const bool extra = peerBytes > kExtraPaddingKeyBytes;
  const size_t padding = paddingFor(tx.size() - headerEnd + (extra ? 1 : 0), plainBlock, ownBytes);
  appendPadding(tx, padding, extra);
  const size_t plainLength = tx.size() - headerEnd + ownBytes;
  const size_t blocks = plainLength / plainBlock;
  // The size of the message as sent (encrypted), which the signature covers.
  const size_t signedEnd = tx.size();
  tx.resize(headerEnd + blocks * peerBytes);
  const auto sentSize = static_cast<uint32_t>(tx.size() - start);
  for (int i = 0; i < 4; ++i) tx[start + 4 + i] = static_cast<uint8_t>(sentSize >> (8 * i));
  std::vector<uint8_t> plain(tx.begin() + start, tx.begin() + signedEnd);
  plain.resize(plain.size() + ownBytes);
  const CryptoCalls& c = crypto();
  size_t signatureLength = 0;
  if (!c.rsaSha256Sign(keys.ownKeyPem.data(), keys.ownKeyPem.size(), plain.data(), signedEnd - start, plain.data() + signedEnd - start,
                       ownBytes, &signatureLength) ||
      signatureLength != ownBytes)
    return false;
  const size_t clear = headerEnd - start;
  for (size_t b = 0; b < blocks; ++b) {
    size_t written = 0;
    if (!c.rsaOaepSha1Encrypt(keys.peerCertificate.data(), keys.peerCertificate.size(), plain.data() + clear + b * plainBlock,
                              plainBlock, tx.data() + headerEnd + b * peerBytes, peerBytes, &written) ||
        written != peerBytes)
      return false;
  }
  return true;
}

bool openAsymmetric(std::span<const uint8_t> chunk, size_t headerEnd, const AsymmetricKeys& keys, std::vector<uint8_t>& scratch,
                    std::span<const uint8_t>& plain) {
  const size_t ownBytes = rsaKeyBytes(keys.ownCertificate), peerBytes = rsaKeyBytes(keys.peerCertificate);
  auto secret = chunk.subspan(std::min(headerEnd, chunk.size()));
  if (ownBytes == 0 || peerBytes == 0 || secret.empty() || secret.size() % ownBytes != 0) return false;
  const CryptoCalls& c = crypto();
  scratch.assign(chunk.begin(), chunk.begin() + headerEnd);
  for (size_t at = 0; at < secret.size(); at += ownBytes) {
    const size_t before = scratch.size();
    size_t written = 0;
    scratch.resize(before + ownBytes);
    if (!c.rsaOaepSha1Decrypt(keys.ownKeyPem.data(), keys.ownKeyPem.size(), secret.data() + at, ownBytes, scratch.data() + before,
                              ownBytes, &written))
      return false;
    scratch.resize(before + written);
  }
  if (scratch.size() < headerEnd + peerBytes) return false;
  const size_t signedEnd = scratch.size() - peerBytes;
  if (!c.rsaSha256Verify(keys.peerCertificate.data(), keys.peerCertificate.size(), scratch.data(), signedEnd, scratch.data() + signedEnd,
                         peerBytes))
    return false;
  auto body = std::span<const uint8_t>(scratch).subspan(headerEnd, signedEnd - headerEnd);
  const size_t padding = paddingOf(body, ownBytes > kExtraPaddingKeyBytes);
  if (padding == SIZE_MAX) return false;
  plain = body.first(body.size() - padding);
  return true;
}

}  // namespace virtcom::proto::opcua
