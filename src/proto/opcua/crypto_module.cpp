// The module virtcom-crypto.so: OpenSSL's libcrypto behind the table of crypto_module.hpp.
#include "proto/opcua/crypto_module.hpp"

#include <openssl/bio.h>
#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>
#include <openssl/pem.h>
#include <openssl/rand.h>
#include <openssl/rsa.h>
#include <openssl/x509.h>
#include <openssl/x509v3.h>

#include <climits>
#include <cstring>
#include <ctime>
#include <memory>
#include <string>

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

// OpenSSL objects freed on every return path.
template <typename T, void (*Free)(T*)>
struct Freer {
  void operator()(T* p) const { Free(p); }
};
using Key = std::unique_ptr<EVP_PKEY, Freer<EVP_PKEY, EVP_PKEY_free>>;
using Context = std::unique_ptr<EVP_PKEY_CTX, Freer<EVP_PKEY_CTX, EVP_PKEY_CTX_free>>;
using DigestContext = std::unique_ptr<EVP_MD_CTX, Freer<EVP_MD_CTX, EVP_MD_CTX_free>>;
using CipherContext = std::unique_ptr<EVP_CIPHER_CTX, Freer<EVP_CIPHER_CTX, EVP_CIPHER_CTX_free>>;
using Certificate = std::unique_ptr<X509, Freer<X509, X509_free>>;
using Bio = std::unique_ptr<BIO, Freer<BIO, BIO_free_all>>;
using Names = std::unique_ptr<GENERAL_NAMES, Freer<GENERAL_NAMES, GENERAL_NAMES_free>>;

Certificate parseCertificate(const uint8_t* der, size_t length) {
  const unsigned char* p = der;
  return Certificate(fitsInt(length) ? d2i_X509(nullptr, &p, static_cast<long>(length)) : nullptr);
}

Key publicKeyOf(const uint8_t* der, size_t length) {
  Certificate cert = parseCertificate(der, length);
  return Key(cert ? X509_get_pubkey(cert.get()) : nullptr);
}

Key privateKeyOf(const char* pem, size_t length) {
  if (!fitsInt(length)) return nullptr;
  Bio bio(BIO_new_mem_buf(pem, static_cast<int>(length)));
  return Key(bio ? PEM_read_bio_PrivateKey(bio.get(), nullptr, nullptr, nullptr) : nullptr);
}

bool hmacSha256(const uint8_t* key, size_t keyLength, const uint8_t* data, size_t dataLength, uint8_t* out) {
  unsigned int n = 0;
  return fitsInt(keyLength) && HMAC(EVP_sha256(), key, static_cast<int>(keyLength), data, dataLength, out, &n) && n == 32;
}

bool sha1(const uint8_t* data, size_t length, uint8_t* out) {
  unsigned int n = 0;
  return EVP_Digest(data, length, out, &n, EVP_sha1(), nullptr) == 1 && n == 20;
}

bool aes256Cbc(bool encrypt, const uint8_t* key, const uint8_t* iv, const uint8_t* in, size_t length, uint8_t* out) {
  CipherContext c(EVP_CIPHER_CTX_new());
  int n = 0, last = 0;
  if (!c || length % 16 != 0 || !fitsInt(length) ||
      EVP_CipherInit_ex(c.get(), EVP_aes_256_cbc(), nullptr, key, iv, encrypt ? 1 : 0) != 1 ||
      EVP_CIPHER_CTX_set_padding(c.get(), 0) != 1)
    return false;
  return EVP_CipherUpdate(c.get(), out, &n, in, static_cast<int>(length)) == 1 && EVP_CipherFinal_ex(c.get(), out + n, &last) == 1 &&
         static_cast<size_t>(n + last) == length;
}

// Sets up `c` for OAEP with SHA-1 (OpenSSL's default OAEP digest, set anyway: it is the policy's).
bool useOaepSha1(EVP_PKEY_CTX* c) {
  return EVP_PKEY_CTX_set_rsa_padding(c, RSA_PKCS1_OAEP_PADDING) == 1 && EVP_PKEY_CTX_set_rsa_oaep_md(c, EVP_sha1()) == 1 &&
         EVP_PKEY_CTX_set_rsa_mgf1_md(c, EVP_sha1()) == 1;
}

bool rsaOaepSha1Encrypt(const uint8_t* certificate, size_t certificateLength, const uint8_t* in, size_t length, uint8_t* out,
                        size_t outCapacity, size_t* outLength) {
  Key key = publicKeyOf(certificate, certificateLength);
  Context c(key ? EVP_PKEY_CTX_new(key.get(), nullptr) : nullptr);
  *outLength = outCapacity;
  return c && EVP_PKEY_encrypt_init(c.get()) == 1 && useOaepSha1(c.get()) &&
         EVP_PKEY_encrypt(c.get(), out, outLength, in, length) == 1;
}

bool rsaOaepSha1Decrypt(const char* keyPem, size_t keyPemLength, const uint8_t* in, size_t length, uint8_t* out,
                        size_t outCapacity, size_t* outLength) {
  Key key = privateKeyOf(keyPem, keyPemLength);
  Context c(key ? EVP_PKEY_CTX_new(key.get(), nullptr) : nullptr);
  *outLength = outCapacity;
  return c && EVP_PKEY_decrypt_init(c.get()) == 1 && useOaepSha1(c.get()) &&
         EVP_PKEY_decrypt(c.get(), out, outLength, in, length) == 1;
}

bool rsaSha256Sign(const char* keyPem, size_t keyPemLength, const uint8_t* data, size_t length, uint8_t* out, size_t outCapacity,
                   size_t* outLength) {
  Key key = privateKeyOf(keyPem, keyPemLength);
  DigestContext c(EVP_MD_CTX_new());
  *outLength = outCapacity;
  return key && c && EVP_DigestSignInit(c.get(), nullptr, EVP_sha256(), nullptr, key.get()) == 1 &&
         EVP_DigestSign(c.get(), out, outLength, data, length) == 1;
}

bool rsaSha256Verify(const uint8_t* certificate, size_t certificateLength, const uint8_t* data, size_t length,
                     const uint8_t* signature, size_t signatureLength) {
  Key key = publicKeyOf(certificate, certificateLength);
  DigestContext c(EVP_MD_CTX_new());
  return key && c && EVP_DigestVerifyInit(c.get(), nullptr, EVP_sha256(), nullptr, key.get()) == 1 &&
         EVP_DigestVerify(c.get(), signature, signatureLength, data, length) == 1;
}

bool addExtension(X509* cert, int nid, const char* value) {
  X509V3_CTX v3;
  X509V3_set_ctx_nodb(&v3);
  X509V3_set_ctx(&v3, cert, cert, nullptr, nullptr, 0);
  X509_EXTENSION* ext = X509V3_EXT_conf_nid(nullptr, &v3, nid, value);
  const bool added = ext && X509_add_ext(cert, ext, -1) == 1;
  X509_EXTENSION_free(ext);
  return added;
}

// Subject and issuer, the extensions OPC 10000-6 §6.2.2 asks of an application instance
// certificate, the signature.
bool fillCertificate(X509* cert, EVP_PKEY* key, const char* commonName, const char* applicationUri, const char* host,
                     uint32_t days) {
  uint8_t serial[16];
  if (RAND_bytes(serial, sizeof serial) != 1) return false;
  serial[0] &= 0x7f;  // positive
  BIGNUM* bn = BN_bin2bn(serial, sizeof serial, nullptr);
  const bool serialSet = bn && BN_to_ASN1_INTEGER(bn, X509_get_serialNumber(cert));
  BN_free(bn);
  X509_NAME* name = X509_get_subject_name(cert);
  const std::string san = std::string("URI:") + applicationUri + ",DNS:" + host;
  return serialSet && X509_set_version(cert, 2) == 1 && X509_gmtime_adj(X509_getm_notBefore(cert), -60) &&
         X509_gmtime_adj(X509_getm_notAfter(cert), static_cast<long>(days) * 86400) &&
         X509_NAME_add_entry_by_txt(name, "CN", MBSTRING_UTF8, reinterpret_cast<const unsigned char*>(commonName), -1, -1, 0) == 1 &&
         X509_NAME_add_entry_by_txt(name, "O", MBSTRING_UTF8, reinterpret_cast<const unsigned char*>("virtcom"), -1, -1, 0) == 1 &&
         X509_set_issuer_name(cert, name) == 1 && X509_set_pubkey(cert, key) == 1 &&
         addExtension(cert, NID_subject_key_identifier, "hash") && addExtension(cert, NID_authority_key_identifier, "keyid") &&
         addExtension(cert, NID_basic_constraints, "critical,CA:FALSE") &&
         addExtension(cert, NID_key_usage, "critical,digitalSignature,nonRepudiation,keyEncipherment,dataEncipherment,keyCertSign") &&
         addExtension(cert, NID_ext_key_usage, "serverAuth,clientAuth") && addExtension(cert, NID_subject_alt_name, san.c_str()) &&
         X509_sign(cert, key, EVP_sha256()) > 0;
}

bool makeCertificate(const char* commonName, const char* applicationUri, const char* host, uint32_t days, uint8_t* certificate,
                     size_t certificateCapacity, size_t* certificateLength, char* keyPem, size_t keyPemCapacity,
                     size_t* keyPemLength) {
  Key key(EVP_RSA_gen(2048));
  Certificate cert(X509_new());
  if (!key || !cert || !fillCertificate(cert.get(), key.get(), commonName, applicationUri, host, days)) return false;
  const int derLength = i2d_X509(cert.get(), nullptr);
  if (derLength <= 0 || static_cast<size_t>(derLength) > certificateCapacity) return false;
  unsigned char* p = certificate;
  *certificateLength = static_cast<size_t>(i2d_X509(cert.get(), &p));
  Bio bio(BIO_new(BIO_s_mem()));
  if (!bio || PEM_write_bio_PrivateKey(bio.get(), key.get(), nullptr, nullptr, 0, nullptr, nullptr) != 1) return false;
  char* pem = nullptr;
  const long pemLength = BIO_get_mem_data(bio.get(), &pem);
  if (pemLength <= 0 || static_cast<size_t>(pemLength) > keyPemCapacity) return false;
  std::memcpy(keyPem, pem, static_cast<size_t>(pemLength));
  *keyPemLength = static_cast<size_t>(pemLength);
  return true;
}

int64_t unixSeconds(const ASN1_TIME* t) {
  struct tm tm {};
  return ASN1_TIME_to_tm(t, &tm) == 1 ? static_cast<int64_t>(timegm(&tm)) : 0;
}

bool certificateFacts(const uint8_t* certificate, size_t certificateLength, int64_t* notBefore, int64_t* notAfter, char* uri,
                      size_t uriCapacity, size_t* uriLength, uint32_t* rsaBits) {
  Certificate cert = parseCertificate(certificate, certificateLength);
  if (!cert) return false;
  *notBefore = unixSeconds(X509_get0_notBefore(cert.get()));
  *notAfter = unixSeconds(X509_get0_notAfter(cert.get()));
  *uriLength = 0;
  Names names(static_cast<GENERAL_NAMES*>(X509_get_ext_d2i(cert.get(), NID_subject_alt_name, nullptr, nullptr)));
  for (int i = 0; names && i < sk_GENERAL_NAME_num(names.get()); ++i) {
    const GENERAL_NAME* n = sk_GENERAL_NAME_value(names.get(), i);
    if (n->type != GEN_URI) continue;
    const size_t length = static_cast<size_t>(ASN1_STRING_length(n->d.uniformResourceIdentifier));
    if (length > uriCapacity) return false;
    std::memcpy(uri, ASN1_STRING_get0_data(n->d.uniformResourceIdentifier), length);
    *uriLength = length;
    break;
  }
  const EVP_PKEY* key = X509_get0_pubkey(cert.get());
  *rsaBits = key && EVP_PKEY_get_base_id(key) == EVP_PKEY_RSA ? static_cast<uint32_t>(EVP_PKEY_get_bits(key)) : 0;
  return true;
}

constexpr CryptoCalls kCalls{pbkdf2Sha256,      randomBytes,        equalInConstantTime, hmacSha256,    sha1,
                             aes256Cbc,         rsaOaepSha1Encrypt, rsaOaepSha1Decrypt,  rsaSha256Sign, rsaSha256Verify,
                             makeCertificate,   certificateFacts};

}  // namespace
}  // namespace virtcom::proto::opcua

extern "C" __attribute__((visibility("default"))) const virtcom::proto::opcua::CryptoCalls* virtcomCryptoCalls() {
  return &virtcom::proto::opcua::kCalls;
}
