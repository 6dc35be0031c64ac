#include "proto/opcua/client_security.hpp"

#include "proto/opcua/crypto.hpp"
#include "proto/opcua/services.hpp"

namespace virtcom::proto::opcua {

namespace {

// RSA-OAEP with SHA-1 takes 2 * 20 + 2 bytes of every block (RFC 8017 §7.1.1).
constexpr size_t kOaepSha1Overhead = 42;

bool decodeBytes(Reader& r, std::vector<uint8_t>& out) {
  ByteString b;
  if (!decode(r, b)) return false;
  out.assign(b.bytes.begin(), b.bytes.end());
  return true;
}

bool decodeEndpoint(Reader& r, EndpointInfo& e) {
  uint32_t tokens = 0;
  std::string ignored;
  if (!decode(r, ignored) || !skipApplicationDescription(r) || !decodeBytes(r, e.certificate) || !r.u32(e.mode) ||
      !decode(r, e.securityPolicyUri) || !r.arrayLength(tokens, 4))
    return false;
  e.tokens.resize(tokens);
  for (UserTokenPolicyInfo& t : e.tokens)
    if (!decode(r, t.policyId) || !r.u32(t.tokenType) || !decode(r, ignored) || !decode(r, ignored) || !decode(r, t.securityPolicyUri))
      return false;
  uint8_t level = 0;
  return decode(r, ignored) && r.u8(level);  // TransportProfileUri, SecurityLevel
}

// MessageSecurityMode's name (OPC 10000-4 §7.20).
std::string modeWord(uint32_t mode) {
  return mode == static_cast<uint32_t>(SecurityMode::Sign)             ? "Sign"
         : mode == static_cast<uint32_t>(SecurityMode::SignAndEncrypt) ? "SignAndEncrypt"
                                                                       : "mode " + std::to_string(mode);
}

// "None" or the policy's name and the mode: "Basic256Sha256 Sign".
std::string endpointSecurityName(const std::string& policyUri, uint32_t mode) {
  if (mode == kSecurityModeNone) return "None";
  return policyUri.substr(policyUri.rfind('#') + 1) + " " + modeWord(mode);
}

std::vector<uint8_t> joined(std::span<const uint8_t> first, std::span<const uint8_t> second) {
  std::vector<uint8_t> data(first.begin(), first.end());
  data.insert(data.end(), second.begin(), second.end());
  return data;
}

}  // namespace

bool decodeEndpoints(Reader& r, std::vector<EndpointInfo>& out) {
  uint32_t n = 0;
  if (!r.arrayLength(n, 4)) return false;
  out.resize(n);
  for (EndpointInfo& e : out)
    if (!decodeEndpoint(r, e)) return false;
  return true;
}

std::string securityModeName(SecurityMode mode) {
  return endpointSecurityName(kSecurityPolicyBasic256Sha256, static_cast<uint32_t>(mode));
}

std::expected<const EndpointInfo*, std::string> pickEndpoint(std::span<const EndpointInfo> endpoints, SecurityMode mode,
                                                             const std::string& url) {
  const char* policy = mode == SecurityMode::None ? kSecurityPolicyNone : kSecurityPolicyBasic256Sha256;
  std::string offered;
  for (const EndpointInfo& e : endpoints) {
    if (e.mode == static_cast<uint32_t>(mode) && e.securityPolicyUri == policy) return &e;
    offered += (offered.empty() ? "" : ", ") + endpointSecurityName(e.securityPolicyUri, e.mode);
  }
  return std::unexpected("the server at " + url + " has no endpoint with security " + securityModeName(mode) + "; it offers " +
                         (offered.empty() ? "none" : offered));
}

std::vector<uint8_t> signBoth(const std::string& keyPem, std::span<const uint8_t> first, std::span<const uint8_t> second) {
  const std::vector<uint8_t> data = joined(first, second);
  std::vector<uint8_t> signature(512);  // up to RSA-4096
  size_t length = 0;
  if (!crypto().rsaSha256Sign(keyPem.data(), keyPem.size(), data.data(), data.size(), signature.data(), signature.size(), &length))
    return {};
  signature.resize(length);
  return signature;
}

bool verifyBoth(std::span<const uint8_t> certificate, std::span<const uint8_t> first, std::span<const uint8_t> second,
                std::span<const uint8_t> signature) {
  const std::vector<uint8_t> data = joined(first, second);
  return crypto().rsaSha256Verify(certificate.data(), certificate.size(), data.data(), data.size(), signature.data(), signature.size());
}

std::vector<uint8_t> encryptPassword(std::string_view password, std::span<const uint8_t> serverNonce,
                                     std::span<const uint8_t> serverCertificate) {
  const size_t keyBytes = rsaKeyBytes(serverCertificate);
  if (keyBytes <= kOaepSha1Overhead) return {};
  const auto length = static_cast<uint32_t>(password.size() + serverNonce.size());
  std::vector<uint8_t> plain{static_cast<uint8_t>(length), static_cast<uint8_t>(length >> 8), static_cast<uint8_t>(length >> 16),
                             static_cast<uint8_t>(length >> 24)};
  plain.insert(plain.end(), password.begin(), password.end());
  plain.insert(plain.end(), serverNonce.begin(), serverNonce.end());
  const size_t block = keyBytes - kOaepSha1Overhead;
  std::vector<uint8_t> secret((plain.size() + block - 1) / block * keyBytes);
  for (size_t b = 0; b * block < plain.size(); ++b) {
    size_t written = 0;
    if (!crypto().rsaOaepSha1Encrypt(serverCertificate.data(), serverCertificate.size(), plain.data() + b * block,
                                     std::min(block, plain.size() - b * block), secret.data() + b * keyBytes, keyBytes, &written) ||
        written != keyBytes)
      return {};
  }
  return secret;
}

}  // namespace virtcom::proto::opcua
