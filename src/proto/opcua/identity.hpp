#pragma once
// User identities (docs/opcua.md, Users and roles): the UserTokenPolicies an endpoint announces
// and the check of the UserIdentityToken a client sends in ActivateSession (OPC 10000-4 §5.7.3,
// §7.41): anonymous, or a user name and password from the users file (`--opcua-users`).
#include <cstdint>
#include <span>

#include "proto/opcua/binary_codec.hpp"
#include "proto/opcua/server_core.hpp"

namespace virtcom::proto::opcua {

// The UserIdentityTokens array of an EndpointDescription: what `config` accepts.
void encodeUserTokenPolicies(Writer& w, const ServerConfig& config);

// What the password check needs of the session and its channel.
struct IdentitySecurity {
  std::span<const uint8_t> serverNonce;  // the session's last nonce, which an encrypted password ends with
  bool channelEncrypted = false;         // mode SignAndEncrypt: a password may come unencrypted
};

// What the identity in `token` may do (never None), or a Bad status: BadIdentityTokenInvalid for
// a token this server does not accept (a type or policy not announced, anonymous when refused,
// a malformed token, a password encrypted without a PKI folder or in clear where the policy
// asks for it encrypted), BadUserAccessDenied for an unknown user or a wrong password (the same
// for both, not to tell a guesser which one was wrong). With a PKI folder (--opcua-pki) the
// password comes encrypted with the server's key (RSA-OAEP, OPC 10000-4 §7.41.2.2).
uint32_t checkIdentity(const ServerConfig& config, const ExtensionObject& token, UserAccess& access,
                       const IdentitySecurity& security = {});

}  // namespace virtcom::proto::opcua
