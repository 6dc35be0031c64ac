#pragma once
// Security policy Basic256Sha256 (OPC 10000-7, "SecurityPolicy [A] - Basic256Sha256"; the
// message security of OPC 10000-6 §6.7): the keys of a channel derived from its two nonces with
// P_SHA256, and chunks signed with HMAC-SHA256 and encrypted with AES-256-CBC (symmetric), or
// signed with RSA-PKCS1-v1_5-SHA256 and encrypted with RSA-OAEP-SHA1 (asymmetric, OpenSecureChannel).
// The primitives come from the crypto module (crypto.hpp).
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace virtcom::proto::opcua {

inline constexpr const char* kSecurityPolicyBasic256Sha256 = "http://opcfoundation.org/UA/SecurityPolicy#Basic256Sha256";
// MessageSecurityMode (OPC 10000-4 §7.20).
enum class SecurityMode : uint32_t { None = 1, Sign = 2, SignAndEncrypt = 3 };

inline constexpr size_t kSecureNonceBytes = 32;      // the policy's SecureChannelNonceLength
inline constexpr size_t kSymmetricSignatureBytes = 32;  // HMAC-SHA256
inline constexpr size_t kAesBlockBytes = 16;
// Message header (8), channel id (4), token id (4): what a symmetric chunk sends in clear.
inline constexpr size_t kSymmetricClearBytes = 16;

// One direction's keys (OPC 10000-6 §6.7.5).
struct SymmetricKeys {
  std::array<uint8_t, 32> signing{};
  std::array<uint8_t, 32> encrypting{};
  std::array<uint8_t, 16> iv{};
};

// P_SHA256(secret, seed) of RFC 5246 §5, `length` bytes. False if the crypto module fails.
bool pSha256(std::span<const uint8_t> secret, std::span<const uint8_t> seed, std::span<uint8_t> out);
// The keys of one direction: the signing key, the encrypting key and the IV, in this order, cut
// from P_SHA256(secret, seed). The client's keys (what the client sends with) have the server's
// nonce as secret and the client's as seed; the server's the other way round.
bool deriveKeys(std::span<const uint8_t> secret, std::span<const uint8_t> seed, SymmetricKeys& out);

// The padding after a plaintext of `length` bytes (from the sequence header on) so that it, one
// PaddingSize byte, the padding and a `signatureBytes` signature fill whole `blockBytes` blocks:
// the PaddingSize value (the count of padding bytes after the PaddingSize byte).
size_t paddingFor(size_t length, size_t blockBytes, size_t signatureBytes);

// The body bytes a symmetric chunk of `bufferBytes` can carry after its headers (message header,
// channel and token ids, sequence header): secured, it also carries the signature and, encrypted,
// whole AES blocks with at least one padding byte.
size_t symmetricChunkRoom(size_t bufferBytes, SecurityMode mode);

// Whether a secured channel's sequence number `next` follows `last` (OPC 10000-6 §6.7.2.4): by
// one, or wrapped to below 1024 once it passed UInt32 max - 1024.
bool sequenceNumberFollows(uint32_t last, uint32_t next);

// Secures the chunk `tx[start..]` in place, which holds the message header, the channel and
// token ids, the sequence header and the body: pads it (SignAndEncrypt), patches its size, signs
// it and encrypts it from the sequence header on. Allocates only if `tx` must grow.
bool sealSymmetric(std::vector<uint8_t>& tx, size_t start, SecurityMode mode, const SymmetricKeys& keys);
// The reverse of sealSymmetric on a received chunk (decrypted in place): false if it was not
// signed with `keys` or its padding is wrong; else `plain` is the sequence header and body.
bool openSymmetric(std::span<uint8_t> chunk, SecurityMode mode, const SymmetricKeys& keys, std::span<const uint8_t>& plain);

// The local side of the asymmetric algorithms: the application instance certificate (DER) and
// its private key (PEM), and the peer's certificate (DER).
struct AsymmetricKeys {
  std::vector<uint8_t> ownCertificate;
  std::string ownKeyPem;
  std::vector<uint8_t> peerCertificate;
};
// The longest application URI the server reads from a certificate.
inline constexpr size_t kMaxCertificateUri = 4096;
// The RSA key size in bytes of a DER certificate (0 if not RSA or unreadable).
size_t rsaKeyBytes(std::span<const uint8_t> certificate);

// Secures the OPN chunk `tx[start..]` in place, which holds the message header, the asymmetric
// security header (`headerEnd` is where it ends), the sequence header and the body: pads it to
// whole RSA-OAEP blocks of the peer's key, patches the size, signs it with the own key and
// encrypts it with the peer's certificate.
bool sealAsymmetric(std::vector<uint8_t>& tx, size_t start, size_t headerEnd, const AsymmetricKeys& keys);
// The reverse on a received OPN chunk whose asymmetric security header ends at `headerEnd`:
// decrypted with the own key into `plain` (sequence header and body) after the signature was
// checked with the peer's certificate.
bool openAsymmetric(std::span<const uint8_t> chunk, size_t headerEnd, const AsymmetricKeys& keys, std::vector<uint8_t>& scratch,
                    std::span<const uint8_t>& plain);

}  // namespace virtcom::proto::opcua
