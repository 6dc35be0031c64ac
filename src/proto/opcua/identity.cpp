#include "proto/opcua/identity.hpp"

#include <algorithm>

#include "proto/opcua/node_ids.hpp"

namespace virtcom::proto::opcua {

namespace {

// UserTokenType (OPC 10000-4 §7.43) and the policy ids this server gives its two tokens.
constexpr uint32_t kTokenAnonymous = 0, kTokenUserName = 1;
constexpr const char* kAnonymousPolicyId = "anonymous";
constexpr const char* kUserNamePolicyId = "username";

constexpr uint32_t bad(StatusCodeValue s) { return static_cast<uint32_t>(s); }

void encodePolicy(Writer& w, const char* policyId, uint32_t tokenType) {
  w.string(policyId);
  w.u32(tokenType);
  w.nullString();  // IssuedTokenType
  w.nullString();  // IssuerEndpointUrl
  // SecurityPolicyUri: null, that of the channel. With policy None the password crosses the wire
  // as it is (docs/security.md, OPC UA).
  w.nullString();
}

// UserNameIdentityToken (OPC 10000-4 §7.41.3): PolicyId, UserName, Password, EncryptionAlgorithm.
uint32_t checkUserName(const ServerConfig& config, const ExtensionObject& token, UserAccess& access) {
  if (config.users.empty() || token.body != ExtensionObject::Body::Binary) return bad(StatusCodeValue::BadIdentityTokenInvalid);
  Reader in(std::span(reinterpret_cast<const uint8_t*>(token.bytes.data()), token.bytes.size()));
  std::string policyId, user, algorithm;
  ByteString password;
  if (!decode(in, policyId) || !decode(in, user) || !decode(in, password) || !decode(in, algorithm))
    return bad(StatusCodeValue::BadIdentityTokenInvalid);
  // An encrypted password needs a security policy other than None: none is announced.
  if (policyId != kUserNamePolicyId || !algorithm.empty()) return bad(StatusCodeValue::BadIdentityTokenInvalid);
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
  if (anonymous) encodePolicy(w, kAnonymousPolicyId, kTokenAnonymous);
  if (userName) encodePolicy(w, kUserNamePolicyId, kTokenUserName);
}

uint32_t checkIdentity(const ServerConfig& config, const ExtensionObject& token, UserAccess& access) {
  uint32_t status = 0;
  // A null token is anonymous too (OPC 10000-4 §5.7.3.2).
  if (token.typeId.isNull() || token.typeId == NodeId::num(0, ids::kAnonymousIdentityToken)) {
    if (config.anonymous == UserAccess::None) return bad(StatusCodeValue::BadIdentityTokenInvalid);
    access = config.anonymous;
  } else if (token.typeId == NodeId::num(0, ids::kUserNameIdentityToken)) {
    if ((status = checkUserName(config, token, access)) != 0) return status;
  } else {
    return bad(StatusCodeValue::BadIdentityTokenInvalid);
  }
  if (config.readOnly) access = std::min(access, UserAccess::Read);
  return 0;
}

}  // namespace virtcom::proto::opcua
