// `virtcom opcua-user add FILE USER`: adds a user to an OPC UA users file (`--opcua-users`), or
// sets the password and role of one already there, with the password read from stdin so it never
// shows in the shell history or the process list (docs/opcua.md, Users and roles).
#include <sys/stat.h>

#include <iostream>
#include <string>

#include "cli/commands.hpp"
#include "cli/common.hpp"
#include "cli/opcua_options.hpp"
#include "proto/opcua/crypto.hpp"

namespace virtcom::cli {

namespace {

namespace ua = proto::opcua;

struct UserOptions {
  std::string file, user, role = "read-only";
};

// The password: the first line of stdin, without its line end.
std::string readPassword() {
  std::string password;
  std::getline(std::cin, password);
  if (!password.empty() && password.back() == '\r') password.pop_back();
  return password;
}

ExitCode addUser(const UserOptions& o) {
  if (!ua::validUserName(o.user)) {
    std::cerr << "error: user name '" << o.user << "': expected letters, digits or punctuation other than ':'\n";
    return ExitCode::Usage;
  }
  auto accounts = readOpcuaUsers(o.file, true);
  if (!accounts) {
    std::cerr << accounts.error() << "\n";
    return ExitCode::InputError;
  }
  if (auto crypto = ua::loadCrypto(); !crypto) {
    std::cerr << "error: hashing the password needs " << crypto.error() << "\n";
    return ExitCode::Usage;
  }
  const std::string password = readPassword();
  if (password.empty()) {
    std::cerr << "error: no password on stdin: expected it on the first line "
                 "(e.g. `read -rs P; echo \"$P\" | virtcom opcua-user add ...`)\n";
    return ExitCode::Usage;
  }
  ua::UserAccess access = ua::UserAccess::Read;
  ua::parseUserAccess(o.role, access);
  ua::UserAccount account = ua::makeUserAccount(o.user, access, password);
  bool replaced = false;
  for (ua::UserAccount& a : *accounts)
    if (a.name == o.user) {
      a = account;
      replaced = true;
    }
  if (!replaced) accounts->push_back(account);
  std::string text = "# OPC UA users of virtcom (--opcua-users): NAME:ROLE:pbkdf2-sha256:ITERATIONS:SALT:HASH\n";
  for (const ua::UserAccount& a : *accounts) text += ua::formatUserAccount(a) + "\n";
  if (!writeFile(o.file, text)) return ExitCode::Usage;
  chmod(o.file.c_str(), S_IRUSR | S_IWUSR);  // the hashes are for the server's eyes only
  std::cerr << (replaced ? "updated " : "added ") << o.user << " (" << o.role << ") in " << o.file << "\n";
  return ExitCode::Ok;
}

}  // namespace

void addOpcuaUserCommand(CLI::App& app, std::function<void(ExitCode)> setExit) {
  CLI::App* users = app.add_subcommand("opcua-user", "Manage the OPC UA users file of --opcua-users (docs/opcua.md, Users and roles)");
  users->require_subcommand(1);
  auto o = std::make_shared<UserOptions>();
  CLI::App* add = users->add_subcommand(
      "add", "Add a user (or set the password and role of one), reading the password from the first line of stdin");
  add->add_option("file", o->file, "the users file (created if missing, readable by its owner only)")->required();
  add->add_option("user", o->user, "the user name (no ':' and no spaces)")->required();
  add->add_option("--role", o->role, "read-only (default: browse, read, subscribe) or read-write (also write)")
      ->check(CLI::IsMember({"read-only", "read-write"}));
  add->callback([o, setExit] { setExit(addUser(*o)); });
}

}  // namespace virtcom::cli
