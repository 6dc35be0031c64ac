#pragma once
// The interface between the OPC UA stack (crypto.cpp, in the executable) and the module
// virtcom-crypto.so (crypto_module.cpp), the only code that calls OpenSSL's libcrypto. Linked
// into the executable, libcrypto was loaded and initialised by every command, about 2.5 ms of
// CPU per process (docs/performance.md, "Start-up"); as a module it is loaded only by what hashes
// passwords: an OPC UA server with a users file and `virtcom opcua-user`.
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
};

// The module's one function (extern "C", found by name).
using GetCryptoCalls = const CryptoCalls* (*)();
inline constexpr const char* kCryptoModule = "virtcom-crypto.so";
inline constexpr const char* kCryptoCallsSymbol = "virtcomCryptoCalls";

}  // namespace virtcom::proto::opcua
