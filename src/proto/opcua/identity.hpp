#pragma once
// User identities (docs/opcua.md, Users and roles): the UserTokenPolicies an endpoint announces
// and the check of the UserIdentityToken a client sends in ActivateSession (OPC 10000-4 §5.7.3,
// §7.41): anonymous, or a user name and password from the users file (`--opcua-users`).
#include <cstdint>

#include "proto/opcua/binary_codec.hpp"
#include "proto/opcua/server_core.hpp"

namespace virtcom::proto::opcua {

// The UserIdentityTokens array of an EndpointDescription: what `config` accepts.
void encodeUserTokenPolicies(Writer& w, const ServerConfig& config);

// What the identity in `token` may do (never None), or a Bad status: BadIdentityTokenInvalid for
// a token this server does not accept (a type or policy not announced, anonymous when refused,
// a malformed or encrypted token), BadUserAccessDenied for an unknown user or a wrong password
// (the same for both, not to tell a guesser which one was wrong).
uint32_t checkIdentity(const ServerConfig& config, const ExtensionObject& token, UserAccess& access);

}  // namespace virtcom::proto::opcua
