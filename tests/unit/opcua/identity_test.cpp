// User identities at ActivateSession: what each configuration accepts and refuses with which
// status, and the UserTokenPolicies an endpoint announces (golden bytes).
#include "proto/opcua/identity.hpp"

#include <gtest/gtest.h>

#include "proto/opcua/node_ids.hpp"

namespace virtcom::proto::opcua {
namespace {

using Bytes = std::vector<uint8_t>;

constexpr uint32_t kInvalid = 0x80200000, kDenied = 0x801F0000;  // BadIdentityTokenInvalid, BadUserAccessDenied

// A UserNameIdentityToken: PolicyId, UserName, Password, EncryptionAlgorithm.
ExtensionObject userName(std::string_view user, std::string_view password, std::string_view policy = "username",
                         std::string_view algorithm = {}) {
  Bytes b;
  Writer w(b);
  w.string(std::string(policy));
  w.string(std::string(user));
  w.string(std::string(password));
  if (algorithm.empty()) w.nullString();
  else w.string(std::string(algorithm));
  return {NodeId::num(0, ids::kUserNameIdentityToken), ExtensionObject::Body::Binary, std::string(b.begin(), b.end())};
}

const ExtensionObject kAnonymous{NodeId::num(0, ids::kAnonymousIdentityToken), ExtensionObject::Body::Binary,
                                 std::string("\x09\x00\x00\x00anonymous", 13)};

ServerConfig withUsers() {
  ServerConfig c;
  c.users = {makeUserAccount("op", UserAccess::Write, "pw", 10000), makeUserAccount("viewer", UserAccess::Read, "view", 10000)};
  c.anonymous = UserAccess::None;
  return c;
}

TEST(Identity, AnonymousReadsByDefaultWritesOnlyWhenConfiguredAndIsRefusedWithUsers) {
  UserAccess access = UserAccess::None;
  EXPECT_EQ(checkIdentity(ServerConfig{}, kAnonymous, access), 0u);
  EXPECT_EQ(access, UserAccess::Read) << "writing is disabled for anonymous unless configured (issue 20)";
  EXPECT_EQ(checkIdentity(ServerConfig{}, ExtensionObject{}, access), 0u) << "a null token is anonymous";
  EXPECT_EQ(access, UserAccess::Read);
  ServerConfig writeAnonymous;
  writeAnonymous.anonymous = UserAccess::Write;
  EXPECT_EQ(checkIdentity(writeAnonymous, kAnonymous, access), 0u);
  EXPECT_EQ(access, UserAccess::Write);
  EXPECT_EQ(checkIdentity(withUsers(), kAnonymous, access), kInvalid);
  ServerConfig readAnonymous = withUsers();
  readAnonymous.anonymous = UserAccess::Read;
  EXPECT_EQ(checkIdentity(readAnonymous, kAnonymous, access), 0u);
  EXPECT_EQ(access, UserAccess::Read);
}

TEST(Identity, UsersGetTheirRoleAndWrongPasswordsAreDenied) {
  const ServerConfig c = withUsers();
  UserAccess access = UserAccess::None;
  EXPECT_EQ(checkIdentity(c, userName("op", "pw"), access), 0u);
  EXPECT_EQ(access, UserAccess::Write);
  EXPECT_EQ(checkIdentity(c, userName("viewer", "view"), access), 0u);
  EXPECT_EQ(access, UserAccess::Read);
  EXPECT_EQ(checkIdentity(c, userName("op", "wrong"), access), kDenied);
  EXPECT_EQ(checkIdentity(c, userName("nobody", "pw"), access), kDenied) << "the same status as a wrong password";
  ServerConfig readOnly = c;
  readOnly.readOnly = true;
  EXPECT_EQ(checkIdentity(readOnly, userName("op", "pw"), access), 0u);
  EXPECT_EQ(access, UserAccess::Read) << "--opcua-readonly caps every role";
}

TEST(Identity, TokensNotAnnouncedAreInvalid) {
  const ServerConfig c = withUsers();
  UserAccess access = UserAccess::None;
  EXPECT_EQ(checkIdentity(c, userName("op", "pw", "other"), access), kInvalid);
  EXPECT_EQ(checkIdentity(c, userName("op", "pw", "username", "http://www.w3.org/2001/04/xmlenc#rsa-oaep"), access), kInvalid);
  ExtensionObject truncated = userName("op", "pw");
  truncated.bytes.resize(truncated.bytes.size() - 2);
  EXPECT_EQ(checkIdentity(c, truncated, access), kInvalid);
  EXPECT_EQ(checkIdentity(ServerConfig{}, userName("op", "pw"), access), kInvalid) << "no users file";
  const ExtensionObject x509{NodeId::num(0, 327), ExtensionObject::Body::Binary, {}};
  EXPECT_EQ(checkIdentity(c, x509, access), kInvalid);
}

TEST(Identity, EndpointAnnouncesWhatIsAccepted) {
  Bytes both, usersOnly;
  ServerConfig c = withUsers();
  Writer u(usersOnly);
  encodeUserTokenPolicies(u, c);
  // One UserTokenPolicy: PolicyId "username", TokenType 1 (UserName), three null strings.
  const Bytes golden{1, 0, 0, 0, 8, 0, 0, 0, 'u', 's', 'e', 'r', 'n', 'a', 'm', 'e', 1, 0, 0, 0,
                     0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff};
  EXPECT_EQ(usersOnly, golden);
  c.anonymous = UserAccess::Read;
  Writer b(both);
  encodeUserTokenPolicies(b, c);
  ASSERT_GE(both.size(), 17u);
  EXPECT_EQ(both[0], 2u);
  EXPECT_EQ(std::string(both.begin() + 8, both.begin() + 17), "anonymous");
}

}  // namespace
}  // namespace virtcom::proto::opcua
