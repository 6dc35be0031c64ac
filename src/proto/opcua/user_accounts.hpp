#pragma once
// The users file of `--opcua-users` (docs/opcua.md, Users and roles): one account a line, a user
// name, a role and a salted PBKDF2-HMAC-SHA256 hash of the password (never the password itself),
//   NAME:ROLE:pbkdf2-sha256:ITERATIONS:SALT_HEX:HASH_HEX
// with ROLE `read-only` or `read-write`; `#` starts a comment line. Hashing and checking use
// OpenSSL's libcrypto through crypto.hpp (the module virtcom-crypto.so): call loadCrypto() first
// to report a missing module; here its absence throws std::runtime_error.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/text_result.hpp"

namespace virtcom::proto::opcua {

// What an identity may do: nothing (refused at ActivateSession), read, or read and write.
enum class UserAccess : uint8_t { None, Read, Write };

struct UserAccount {
  std::string name;
  UserAccess access = UserAccess::Read;
  uint32_t iterations = 0;
  std::vector<uint8_t> salt, hash;
};

// Iterations of a new account's hash: costly for a guesser, and a few ms per ActivateSession.
inline constexpr uint32_t kDefaultHashIterations = 100'000;

// The accounts of a users file's text; an error names `file:line:col`, what is wrong and what
// is expected.
TextResult<std::vector<UserAccount>> parseUserAccounts(std::string_view text, std::string_view file);
// A new account with a random salt (an empty name or a name with ':' or spaces is the caller's to refuse).
UserAccount makeUserAccount(std::string name, UserAccess access, std::string_view password,
                            uint32_t iterations = kDefaultHashIterations);
// The account as a users-file line (without the newline).
std::string formatUserAccount(const UserAccount& account);
// Whether `password` hashes to the account's hash (compared in constant time).
bool passwordMatches(const UserAccount& account, std::string_view password);
// The account named `name`, or nullptr.
const UserAccount* findUserAccount(std::span<const UserAccount> accounts, std::string_view name);
// Whether `name` can be a users-file name: not empty, no ':', no white space or control characters.
bool validUserName(std::string_view name);
// "read-only" / "read-write" / "none" and back (false: not one of them).
const char* userAccessName(UserAccess access);
bool parseUserAccess(std::string_view text, UserAccess& access);

}  // namespace virtcom::proto::opcua
