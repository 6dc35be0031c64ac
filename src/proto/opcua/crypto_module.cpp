// The module virtcom-crypto.so: OpenSSL's libcrypto behind the table of crypto_module.hpp.
#include "proto/opcua/crypto_module.hpp"

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/rand.h>

#include <climits>

namespace virtcom::proto::opcua {
namespace {

bool fitsInt(size_t n) { return n <= static_cast<size_t>(INT_MAX); }

bool pbkdf2Sha256(const char* password, size_t passwordLength, const uint8_t* salt, size_t saltLength, uint32_t iterations,
                  uint8_t* out, size_t outLength) {
  if (!fitsInt(passwordLength) || !fitsInt(saltLength) || !fitsInt(outLength) || iterations > INT_MAX) return false;
  return PKCS5_PBKDF2_HMAC(password, static_cast<int>(passwordLength), salt, static_cast<int>(saltLength),
                           static_cast<int>(iterations), EVP_sha256(), static_cast<int>(outLength), out) == 1;
}

bool randomBytes(uint8_t* out, size_t length) { return fitsInt(length) && RAND_bytes(out, static_cast<int>(length)) == 1; }

bool equalInConstantTime(const uint8_t* a, const uint8_t* b, size_t length) { return CRYPTO_memcmp(a, b, length) == 0; }

constexpr CryptoCalls kCalls{pbkdf2Sha256, randomBytes, equalInConstantTime};

}  // namespace
}  // namespace virtcom::proto::opcua

extern "C" __attribute__((visibility("default"))) const virtcom::proto::opcua::CryptoCalls* virtcomCryptoCalls() {
  return &virtcom::proto::opcua::kCalls;
}
