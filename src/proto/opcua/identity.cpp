#include "proto/opcua/identity.hpp"

#include <algorithm>

#include "proto/opcua/crypto.hpp"
#include "proto/opcua/node_ids.hpp"

namespace virtcom::proto::opcua {

namespace {

// UserTokenType (OPC 10000-4 §7.43) and the policy ids this server gives its two tokens.
constexpr uint32_t kTokenAnonymous = 0, kTokenUserName = 1;
constexpr const char* kAnonymousPolicyId = "anonymous";
constexpr const char* kUserNamePolicyId = "username";

constexpr uint32_t bad(StatusCodeValue s) { return static_cast<uint32_t>(s); }

constexpr const char* kRsaOaep = "http://www.w3.org/2001/04/xmlenc#rsa-oaep";

void encodePolicy(Writer& w, const char* policyId, uint32_t tokenType, const char* securityPolicy) {
  w.string(policyId);
  w.u32(tokenType);
  w.nullString();  // IssuedTokenType
  w.nullString();  // IssuerEndpointUrl
  // SecurityPolicyUri: null, that of the channel (with policy None the password crosses the wire
  // as it is, docs/security.md), or Basic256Sha256 on every endpoint, None too.
  if (securityPolicy) w.string(securityPolicy);
  else w.nullString();
}

// The legacy encrypted secret (OPC 10000-4 §7.41.2.2): RSA-OAEP blocks holding the length (of
// what follows), the password and the server nonce. False if it is not that.
bool decryptPassword(const Pki& pki, const ByteString& secret, std::span<const uint8_t> serverNonce, std::string& password) {
  const size_t block = rsaKeyBytes(pki.certificate);
  if (block == 0 || secret.bytes.empty() || secret.bytes.size() % block != 0) return false;
  std::string plain(secret.bytes.size(), '\0');
  size_t used = 0;
  for (size_t at = 0; at < secret.bytes.size(); at += block) {
    size_t written = 0;
    if (!crypto().rsaOaepSha1Decrypt(pki.keyPem.data(), pki.keyPem.size(), secret.view().data() + at,
                                     block, reinterpret_cast<uint8_t*>(plain.data()) + used, plain.size() - used, &written))
      return false;
    used += written;
  }
  if (used < 4) return false;
  const size_t length = static_cast<uint8_t>(plain[0]) | static_cast<uint8_t>(plain[1]) << 8 | static_cast<uint8_t>(plain[2]) << 16 |
                        static_cast<size_t>(static_cast<uint8_t>(plain[3])) << 24;
  if (length != used - 4 || length < serverNonce.size()) return false;
  const auto nonce = std::span(reinterpret_cast<const uint8_t*>(plain.data()) + used - serverNonce.size(), serverNonce.size());
  if (serverNonce.empty() || !crypto().equalInConstantTime(nonce.data(), serverNonce.data(), serverNonce.size())) return false;
  password = plain.substr(4, length - serverNonce.size());
  return true;
}

// UserNameIdentityToken (OPC 10000-4 §7.41.3): PolicyId, UserName, Password, EncryptionAlgorithm.
uint32_t checkUserName(const ServerConfig& config, const ExtensionObject& token, UserAccess& access, const IdentitySecurity& security) {
  if (config.users.empty() || token.body != ExtensionObject::Body::Binary) return bad(StatusCodeValue::BadIdentityTokenInvalid);
  Reader in(token.view());
  std::string policyId, user, algorithm;
  ByteString password;
  if (!decode(in, policyId) || !decode(in, user) || !decode(in, password) || !decode(in, algorithm))
    return bad(StatusCodeValue::BadIdentityTokenInvalid);
  if (policyId != kUserNamePolicyId) return bad(StatusCodeValue::BadIdentityTokenInvalid);
  // With a PKI folder the policy asks for the password encrypted (unless the channel is); without
  // one, no encryption is announced.
  const Pki* pki = config.pki.get();
  if (!algorithm.empty() &&
      (!pki || algorithm != kRsaOaep || !decryptPassword(*pki, password, security.serverNonce, password.bytes)))
    return bad(StatusCodeValue::BadIdentityTokenInvalid);
  if (algorithm.empty() && pki && !security.channelEncrypted) return bad(StatusCodeValue::BadIdentityTokenInvalid);
  const UserAccount* account = findUserAccount(config.users, user);
  // An unknown user costs a hash too, so that the time of the answer does not tell it apart.
  static const UserAccount kNobody = makeUserAccount("", UserAccess::None, "", kDefaultHashIterations);
  if (!passwordMatches(account ? *account : kNobody, password.bytes) || !account) return bad(StatusCodeValue::BadUserAccessDenied);
  access = account->access;
  return 0;
}

}  // namespace

void encodeUserTokenPolicies(Writer& w, const ServerConfig& config) {
  const bool anonymous = config.anonymous != UserAccess::None, userName = !config.users.empty();
  w.i32((anonymous ? 1 : 0) + (userName ? 1 : 0));
  if (anonymous) encodePolicy(w, kAnonymousPolicyId, kTokenAnonymous, nullptr);
  if (userName) encodePolicy(w, kUserNamePolicyId, kTokenUserName, config.pki ? kSecurityPolicyBasic256Sha256 : nullptr);
}

uint32_t checkIdentity(const ServerConfig& config, const ExtensionObject& token, UserAccess& access, const IdentitySecurity& security) {
  uint32_t status = 0;
  // A null token is anonymous too (OPC 10000-4 §5.7.3.2).
  if (token.typeId.isNull() || token.typeId == NodeId::num(0, ids::kAnonymousIdentityToken)) {
    if (config.anonymous == UserAccess::None) return bad(StatusCodeValue::BadIdentityTokenInvalid);
    access = config.anonymous;
  } else if (token.typeId == NodeId::num(0, ids::kUserNameIdentityToken)) {
    if ((status = checkUserName(config, token, access, security)) != 0) return status;
  } else {
    return bad(StatusCodeValue::BadIdentityTokenInvalid);
  }
  if (config.readOnly) access = std::min(access, UserAccess::Read);
  return 0;
}

}  // namespace virtcom::proto::opcua
