#include "proto/opcua/user_accounts.hpp"

#include <charconv>
#include <stdexcept>

#include "proto/opcua/crypto.hpp"

namespace virtcom::proto::opcua {

namespace {

constexpr std::string_view kScheme = "pbkdf2-sha256";
constexpr size_t kSaltBytes = 16, kHashBytes = 32;
// Below this a hash is too cheap to guess against; above, one ActivateSession takes seconds.
constexpr uint32_t kMinIterations = 10'000, kMaxIterations = 10'000'000;

std::vector<uint8_t> pbkdf2(std::string_view password, std::span<const uint8_t> salt, uint32_t iterations, size_t bytes) {
  std::vector<uint8_t> out(bytes);
  if (!crypto().pbkdf2Sha256(password.data(), password.size(), salt.data(), salt.size(), iterations, out.data(), bytes))
    throw std::runtime_error("OpenSSL PBKDF2 failed");
  return out;
}

bool unhex(std::string_view text, std::vector<uint8_t>& out) {
  if (text.empty() || text.size() % 2) return false;
  out.clear();
  for (size_t i = 0; i < text.size(); i += 2) {
    uint8_t b = 0;
    auto [end, ec] = std::from_chars(text.data() + i, text.data() + i + 2, b, 16);
    if (ec != std::errc{} || end != text.data() + i + 2) return false;
    out.push_back(b);
  }
  return true;
}

// One line's fields, each with its 1-based column.
struct Field {
  std::string_view text;
  size_t column;
};

std::vector<Field> splitFields(std::string_view line) {
  std::vector<Field> fields;
  size_t start = 0;
  for (size_t i = 0; i <= line.size(); ++i)
    if (i == line.size() || line[i] == ':') {
      fields.push_back({line.substr(start, i - start), start + 1});
      start = i + 1;
    }
  return fields;
}

// Checks one account line; an empty string when it is good.
std::string parseLine(std::string_view line, UserAccount& a, size_t& column) {
  const std::vector<Field> f = splitFields(line);
  column = 1;
  if (f.size() != 6) return "expected 6 fields NAME:ROLE:pbkdf2-sha256:ITERATIONS:SALT_HEX:HASH_HEX, found " + std::to_string(f.size());
  if (!validUserName(f[0].text)) return "invalid user name: expected letters, digits or punctuation other than ':'";
  a.name = f[0].text;
  column = f[1].column;
  if (!parseUserAccess(f[1].text, a.access) || a.access == UserAccess::None)
    return "unknown role '" + std::string(f[1].text) + "': expected read-only or read-write";
  column = f[2].column;
  if (f[2].text != kScheme) return "unknown hash scheme '" + std::string(f[2].text) + "': expected pbkdf2-sha256";
  column = f[3].column;
  auto [end, ec] = std::from_chars(f[3].text.data(), f[3].text.data() + f[3].text.size(), a.iterations);
  if (ec != std::errc{} || end != f[3].text.data() + f[3].text.size() || a.iterations < kMinIterations || a.iterations > kMaxIterations)
    return "iterations '" + std::string(f[3].text) + "': expected a number from 10000 to 10000000";
  column = f[4].column;
  if (!unhex(f[4].text, a.salt) || a.salt.size() < 8) return "salt: expected at least 8 bytes in hexadecimal";
  column = f[5].column;
  if (!unhex(f[5].text, a.hash) || a.hash.size() != kHashBytes) return "hash: expected 32 bytes in hexadecimal";
  return {};
}

}  // namespace

bool validUserName(std::string_view name) {
  if (name.empty()) return false;
  for (char c : name)
    if (c == ':' || static_cast<unsigned char>(c) <= ' ' || c == 0x7f) return false;
  return true;
}

const char* userAccessName(UserAccess access) {
  switch (access) {
    case UserAccess::None: return "none";
    case UserAccess::Read: return "read-only";
    case UserAccess::Write: return "read-write";
  }
  return "none";
}

bool parseUserAccess(std::string_view text, UserAccess& access) {
  for (UserAccess a : {UserAccess::None, UserAccess::Read, UserAccess::Write})
    if (text == userAccessName(a)) {
      access = a;
      return true;
    }
  return false;
}

TextResult<std::vector<UserAccount>> parseUserAccounts(std::string_view text, std::string_view file) {
  std::vector<UserAccount> accounts;
  size_t lineNo = 0;
  while (!text.empty()) {
    const size_t eol = text.find('\n');
    std::string_view line = text.substr(0, eol);
    text = eol == std::string_view::npos ? std::string_view{} : text.substr(eol + 1);
    ++lineNo;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.empty() || line.front() == '#') continue;
    UserAccount a;
    size_t column = 1;
    std::string error = parseLine(line, a, column);
    if (error.empty() && findUserAccount(accounts, a.name)) {
      column = 1;
      error = "user '" + a.name + "' is listed twice: expected one line per user";
    }
    if (!error.empty())
      return TextResult<std::vector<UserAccount>>::failure(std::string(file) + ":" + std::to_string(lineNo) + ":" +
                                                           std::to_string(column) + ": " + error);
    accounts.push_back(std::move(a));
  }
  return accounts;
}

UserAccount makeUserAccount(std::string name, UserAccess access, std::string_view password, uint32_t iterations) {
  UserAccount a{std::move(name), access, iterations, std::vector<uint8_t>(kSaltBytes), {}};
  if (!crypto().randomBytes(a.salt.data(), a.salt.size())) throw std::runtime_error("OpenSSL RAND_bytes failed");
  a.hash = pbkdf2(password, a.salt, iterations, kHashBytes);
  return a;
}

std::string formatUserAccount(const UserAccount& a) {
  return a.name + ":" + userAccessName(a.access) + ":" + std::string(kScheme) + ":" + std::to_string(a.iterations) + ":" +
         lowerHex(a.salt) + ":" + lowerHex(a.hash);
}

bool passwordMatches(const UserAccount& a, std::string_view password) {
  const std::vector<uint8_t> hash = pbkdf2(password, a.salt, a.iterations, a.hash.size());
  return crypto().equalInConstantTime(hash.data(), a.hash.data(), hash.size());
}

const UserAccount* findUserAccount(std::span<const UserAccount> accounts, std::string_view name) {
  for (const UserAccount& a : accounts)
    if (a.name == name) return &a;
  return nullptr;
}

}  // namespace virtcom::proto::opcua
