#pragma once
// The interface between the OPC UA stack (crypto.cpp, in the executable) and the module
// virtcom-crypto.so (crypto_module.cpp), the only code that calls OpenSSL's libcrypto. Linked
// into the executable, libcrypto was loaded and initialised by every command, about 2.5 ms of
// CPU per process (docs/performance.md, "Start-up"); as a module it is loaded only by what hashes
// passwords or secures channels: an OPC UA server with a users file or a security mode other than
// None, and `virtcom opcua-user`.
// Header-only on purpose: the module needs no symbol of the executable. The table grows with
// the security policies that need more of libcrypto.
#include <cstddef>
#include <cstdint>

namespace virtcom::proto::opcua {

struct CryptoCalls {
  // PBKDF2-HMAC-SHA256 of the password and salt, `outLength` bytes into `out`; false on failure.
  bool (*pbkdf2Sha256)(const char* password, size_t passwordLength, const uint8_t* salt, size_t saltLength,
                       uint32_t iterations, uint8_t* out, size_t outLength);
  // `length` bytes from the cryptographically secure generator; false on failure.
  bool (*randomBytes)(uint8_t* out, size_t length);
  // Whether the two byte strings of `length` bytes are equal, in time independent of where they differ.
  bool (*equalInConstantTime)(const uint8_t* a, const uint8_t* b, size_t length);

  // Security policy Basic256Sha256 (OPC 10000-7). Keys cross as bytes: a certificate as DER, a
  // private key as PEM (the PKI folder's files); each call parses them, which only the
  // asymmetric (rare) messages pay. Variable-length results go to `out` of `outCapacity` bytes,
  // their length to `*outLength`. All return false on failure (bad key, short buffer...).

  // HMAC-SHA256 of `data` with `key`: 32 bytes into `out`.
  bool (*hmacSha256)(const uint8_t* key, size_t keyLength, const uint8_t* data, size_t dataLength, uint8_t* out);
  // SHA-1 of `data`: 20 bytes into `out` (a certificate's thumbprint).
  bool (*sha1)(const uint8_t* data, size_t length, uint8_t* out);
  // AES-256-CBC without padding (the caller pads): `length` is a multiple of 16; `out` may be `in`.
  bool (*aes256Cbc)(bool encrypt, const uint8_t* key, const uint8_t* iv, const uint8_t* in, size_t length, uint8_t* out);
  // RSA-OAEP with SHA-1 of one block: encryption with a certificate's public key, decryption with
  // a private key.
  bool (*rsaOaepSha1Encrypt)(const uint8_t* certificate, size_t certificateLength, const uint8_t* in, size_t length,
                             uint8_t* out, size_t outCapacity, size_t* outLength);
  bool (*rsaOaepSha1Decrypt)(const char* keyPem, size_t keyPemLength, const uint8_t* in, size_t length, uint8_t* out,
                             size_t outCapacity, size_t* outLength);
  // RSA PKCS#1 v1.5 signature with SHA-256, and its check against a certificate's public key.
  bool (*rsaSha256Sign)(const char* keyPem, size_t keyPemLength, const uint8_t* data, size_t length, uint8_t* out,
                        size_t outCapacity, size_t* outLength);
  bool (*rsaSha256Verify)(const uint8_t* certificate, size_t certificateLength, const uint8_t* data, size_t length,
                          const uint8_t* signature, size_t signatureLength);
  // A new RSA-2048 key and a self-signed SHA-256 X.509 v3 certificate for an OPC UA application:
  // subject CN=`commonName`, subjectAltName URI:`applicationUri` and DNS:`host`, valid `days`
  // from now. The certificate as DER into `certificate`, the key as PEM (PKCS#8) into `keyPem`.
  bool (*makeCertificate)(const char* commonName, const char* applicationUri, const char* host, uint32_t days,
                          uint8_t* certificate, size_t certificateCapacity, size_t* certificateLength, char* keyPem,
                          size_t keyPemCapacity, size_t* keyPemLength);
  // What the server checks of a peer's certificate: its validity (Unix seconds), the first URI of
  // its subjectAltName (empty if none) and the size of its RSA key in bits (0: not RSA).
  bool (*certificateFacts)(const uint8_t* certificate, size_t certificateLength, int64_t* notBefore, int64_t* notAfter,
                           char* uri, size_t uriCapacity, size_t* uriLength, uint32_t* rsaBits);
};

// The module's one function (extern "C", found by name).
using GetCryptoCalls = const CryptoCalls* (*)();
inline constexpr const char* kCryptoModule = "virtcom-crypto.so";
inline constexpr const char* kCryptoCallsSymbol = "virtcomCryptoCalls";

}  // namespace virtcom::proto::opcua
