// The users file of --opcua-users: the PBKDF2-HMAC-SHA256 hash against a published known answer,
// lines written and read back, and the file:line:col errors of a wrong file.
#include "proto/opcua/user_accounts.hpp"

#include <gtest/gtest.h>

namespace virtcom::proto::opcua {
namespace {

std::vector<uint8_t> bytes(std::string_view s) { return {s.begin(), s.end()}; }

TEST(UserAccounts, PasswordHashMatchesTheKnownAnswer) {
  // PBKDF2-HMAC-SHA256, P = "password", S = "salt", c = 4096, dkLen = 32: the test vector
  // published with the RFC 6070 vectors for SHA-256.
  UserAccount a{"u", UserAccess::Read, 4096, bytes("salt"),
                {0xc5, 0xe4, 0x78, 0xd5, 0x92, 0x88, 0xc8, 0x41, 0xaa, 0x53, 0x0d, 0xb6, 0x84, 0x5c, 0x4c, 0x8d,
                 0x96, 0x28, 0x93, 0xa0, 0x01, 0xce, 0x4e, 0x11, 0xa4, 0x96, 0x38, 0x73, 0xaa, 0x98, 0x13, 0x4a}};
  EXPECT_TRUE(passwordMatches(a, "password"));
  EXPECT_FALSE(passwordMatches(a, "Password"));
  EXPECT_FALSE(passwordMatches(a, ""));
}

TEST(UserAccounts, NewAccountsReadBackAndHaveTheirOwnSalt) {
  const UserAccount a = makeUserAccount("operator", UserAccess::Write, "s3cret word", 10000);
  const UserAccount b = makeUserAccount("viewer", UserAccess::Read, "s3cret word", 10000);
  EXPECT_NE(a.salt, b.salt);
  EXPECT_NE(a.hash, b.hash);
  const std::string text = "# users\n\n" + formatUserAccount(a) + "\r\n" + formatUserAccount(b) + "\n";
  EXPECT_EQ(text.find("s3cret"), std::string::npos) << "the password itself is never stored";
  auto parsed = parseUserAccounts(text, "users.txt");
  ASSERT_TRUE(parsed) << parsed.error();
  ASSERT_EQ(parsed->size(), 2u);
  EXPECT_EQ((*parsed)[0].name, "operator");
  EXPECT_EQ((*parsed)[0].access, UserAccess::Write);
  EXPECT_EQ((*parsed)[1].access, UserAccess::Read);
  EXPECT_TRUE(passwordMatches((*parsed)[0], "s3cret word"));
  EXPECT_FALSE(passwordMatches((*parsed)[0], "s3cret"));
  EXPECT_EQ(findUserAccount(*parsed, "viewer"), &(*parsed)[1]);
  EXPECT_EQ(findUserAccount(*parsed, "nobody"), nullptr);
}

TEST(UserAccounts, ErrorsNameFileLineColumnAndWhatIsExpected) {
  const std::string good = formatUserAccount(makeUserAccount("op", UserAccess::Read, "pw", 10000));
  const std::string hash = good.substr(good.find(":pbkdf2"));
  struct Case {
    std::string text, error;
  } cases[] = {
      {"op:admin" + hash, "u.txt:1:4: unknown role 'admin': expected read-only or read-write"},
      {"# c\nop:read-only:md5:1:00:00", "u.txt:2:14: unknown hash scheme 'md5': expected pbkdf2-sha256"},
      {"op:read-only", "u.txt:1:1: expected 6 fields NAME:ROLE:pbkdf2-sha256:ITERATIONS:SALT_HEX:HASH_HEX, found 2"},
      {"op:read-only:pbkdf2-sha256:99:00112233445566:00", "u.txt:1:28: iterations '99': expected a number from 10000 to 10000000"},
      {"op:read-only:pbkdf2-sha256:10000:xyz:00", "u.txt:1:34: salt: expected at least 8 bytes in hexadecimal"},
      {"op:read-only:pbkdf2-sha256:10000:0011223344556677:00", "u.txt:1:51: hash: expected 32 bytes in hexadecimal"},
      {good + "\n" + good, "u.txt:2:1: user 'op' is listed twice: expected one line per user"},
      {"a b:read-only" + hash, "u.txt:1:1: invalid user name: expected letters, digits or punctuation other than ':'"},
  };
  for (const Case& c : cases) {
    auto parsed = parseUserAccounts(c.text, "u.txt");
    ASSERT_FALSE(parsed) << c.text;
    EXPECT_EQ(parsed.error(), c.error);
  }
}

}  // namespace
}  // namespace virtcom::proto::opcua
