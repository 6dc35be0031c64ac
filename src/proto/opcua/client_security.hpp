#pragma once
// What the client (client.hpp) needs of a server's endpoints and of Basic256Sha256 beyond the
// channel's message security (security_policy.hpp): the EndpointDescriptions of GetEndpoints and
// CreateSession, the choice of the endpoint of the security mode asked for, the SignatureData of
// CreateSession and ActivateSession (OPC 10000-4 §5.6.2, §5.6.3) and the legacy encrypted
// password secret (OPC 10000-4 §7.41.2.2). The primitives come from the crypto module (crypto.hpp).
#include <cstdint>
#include <expected>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "proto/opcua/binary_codec.hpp"
#include "proto/opcua/security_policy.hpp"

namespace virtcom::proto::opcua {

inline constexpr const char* kRsaSha256SignatureUri = "http://www.w3.org/2001/04/xmldsig-more#rsa-sha256";
inline constexpr const char* kRsaOaepUri = "http://www.w3.org/2001/04/xmlenc#rsa-oaep";

// A UserTokenPolicy (OPC 10000-4 §7.42): its id, UserTokenType and SecurityPolicyUri (empty:
// that of the endpoint).
struct UserTokenPolicyInfo {
  std::string policyId;
  uint32_t tokenType = 0;
  std::string securityPolicyUri;
};

// An EndpointDescription (OPC 10000-4 §7.14), what the client uses of it.
struct EndpointInfo {
  std::vector<uint8_t> certificate;  // DER; empty if the server sent none
  uint32_t mode = 0;                 // MessageSecurityMode
  std::string securityPolicyUri;
  std::vector<UserTokenPolicyInfo> tokens;
};

// An array of EndpointDescriptions; false if malformed.
bool decodeEndpoints(Reader& r, std::vector<EndpointInfo>& out);

// "None", "Basic256Sha256 Sign" or "Basic256Sha256 SignAndEncrypt".
std::string securityModeName(SecurityMode mode);
// The endpoint of `mode` (with Basic256Sha256 unless None), or why there is none: the URL of
// the server and the modes it offers.
std::expected<const EndpointInfo*, std::string> pickEndpoint(std::span<const EndpointInfo> endpoints, SecurityMode mode,
                                                             const std::string& url);

// The RSA-SHA256 signature (PKCS#1 v1.5) with `keyPem` over `first` then `second`; empty if the
// crypto module fails.
std::vector<uint8_t> signBoth(const std::string& keyPem, std::span<const uint8_t> first, std::span<const uint8_t> second);
// Whether `signature` is the certificate's key's RSA-SHA256 signature over `first` then `second`.
bool verifyBoth(std::span<const uint8_t> certificate, std::span<const uint8_t> first, std::span<const uint8_t> second,
                std::span<const uint8_t> signature);

// The legacy secret of a UserNameIdentityToken: RSA-OAEP-SHA1 blocks for the server's
// certificate holding the length (of what follows), the password and the server's session
// nonce. Empty if the certificate is no RSA certificate or the crypto module fails.
std::vector<uint8_t> encryptPassword(std::string_view password, std::span<const uint8_t> serverNonce,
                                     std::span<const uint8_t> serverCertificate);

}  // namespace virtcom::proto::opcua
