#include "cli/opcua_options.hpp"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "proto/ads/plc/module_symbols.hpp"
#include "proto/net/endpoint.hpp"
#include "proto/opcua/crypto.hpp"

namespace virtcom::cli {

void addOpcuaServeOptions(CLI::App* cmd, OpcuaServeOptions& o) {
  cmd->add_option("--opcua", o.listen,
                  "serve the PLC's variables over OPC UA (opc.tcp, security None) on HOST:PORT, e.g. 127.0.0.1:4840 "
                  "(see docs/opcua.md); implies --speed 1");
  cmd->add_option("--opcua-allow", o.allow,
                  "comma-separated IPv4 addresses or networks (10.0.0.0/8) allowed to use --opcua (default: any; required beyond "
                  "loopback unless --allow-any-peer; docs/security.md)");
  cmd->add_flag("--opcua-readonly", o.readOnly, "refuse every OPC UA write (BadUserAccessDenied)");
  cmd->add_option("--opcua-max-sessions", o.maxSessions, "sessions open at once on --opcua (default 32)")->check(CLI::Range(1, 10000));
  cmd->add_option("--opcua-users", o.usersFile,
                  "users file: user names, roles (read-only, read-write) and password hashes for OPC UA UserName identities; "
                  "create entries with `virtcom opcua-user add` (docs/opcua.md, Users and roles)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--opcua-anonymous", o.anonymous,
                  "what an anonymous OPC UA session may do: none (refused), read (browse, read, subscribe) or write (default: read, "
                  "or none with --opcua-users)")
      ->check(CLI::IsMember({"none", "read", "write"}));
}

std::expected<std::vector<proto::opcua::UserAccount>, std::string> readOpcuaUsers(const std::string& path, bool missingIsEmpty) {
  std::error_code ec;
  if (missingIsEmpty && !std::filesystem::exists(path, ec)) return std::vector<proto::opcua::UserAccount>{};
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  if (!in || !(text << in.rdbuf())) return std::unexpected(path + ": cannot read the users file");
  auto accounts = proto::opcua::parseUserAccounts(text.str(), path);
  if (!accounts) return std::unexpected(accounts.error());
  return *accounts;
}

std::expected<std::unique_ptr<OpcuaPlcServer>, std::string> startOpcuaServer(const OpcuaServeOptions& o, const PeerFlags& peers,
                                                                              const bc::Module& module) {
  namespace ua = proto::opcua;
  auto endpoint = proto::net::parseEndpoint(o.listen);
  if (!endpoint) return std::unexpected("--opcua: " + endpoint.error());
  ua::ServerConfig config;
  config.listen = *endpoint;
  config.readOnly = o.readOnly;
  config.maxSessions = o.maxSessions;
  if (!o.usersFile.empty()) {
    auto users = readOpcuaUsers(o.usersFile);
    if (!users) return std::unexpected("--opcua-users: " + users.error());
    if (users->empty()) return std::unexpected("--opcua-users: " + o.usersFile + " lists no user (add one with `virtcom opcua-user add`)");
    if (auto crypto = ua::loadCrypto(); !crypto) return std::unexpected("--opcua-users: the password checks need " + crypto.error());
    config.users = std::move(*users);
    config.anonymous = ua::UserAccess::None;
  }
  static const std::map<std::string, ua::UserAccess> kAnonymous{
      {"none", ua::UserAccess::None}, {"read", ua::UserAccess::Read}, {"write", ua::UserAccess::Write}};
  if (!o.anonymous.empty()) config.anonymous = kAnonymous.at(o.anonymous);
  if (config.anonymous == ua::UserAccess::None && config.users.empty())
    return std::unexpected("--opcua-anonymous none: nobody could log on; give --opcua-users FILE too");
  auto policy = peerPolicy(*endpoint, peers, "opcua", "--opcua", "--opcua-allow", o.allow);
  if (!policy) return std::unexpected(policy.error());
  config.peers = std::move(*policy);
  std::unique_ptr<OpcuaPlcServer> s(new OpcuaPlcServer(proto::ads::buildSymbolTable(module)));
  auto server = ua::Server::start(config, s->table_);
  if (!server) return std::unexpected("--opcua: " + server.error());
  s->server_ = std::move(*server);
  return s;
}

void OpcuaPlcServer::beforeScan(plc::Runtime& runtime, WriteObserver* audit) {
  const bc::Module& m = runtime.module();
  proto::opcua::LiveImage live{{runtime.machine().memory(), m.staticSize}, {runtime.inputImage(), m.inputs.size}};
  if (server_->applyPendingWrites(live, audit) > 0) runtime.inputsTouched();
}

void OpcuaPlcServer::afterScan(plc::Runtime& runtime) {
  server_->publishSnapshot({runtime.machine().memory(), runtime.module().staticSize});
}

void announceOpcuaServer(OpcuaPlcServer& server) {
  const proto::opcua::ServerConfig& c = server.server().config();
  std::string identities;
  if (c.anonymous != proto::opcua::UserAccess::None)
    identities = std::string("anonymous ") + (c.anonymous == proto::opcua::UserAccess::Write ? "read-write" : "read-only");
  if (!c.users.empty())
    identities += (identities.empty() ? "" : ", ") + std::to_string(c.users.size()) + (c.users.size() == 1 ? " user" : " users");
  // One write: tests and scripts wait for the whole line.
  std::cerr << "opcua: serving " + server.server().endpointUrl() + " (security None, " + identities + ")\n";
}

}  // namespace virtcom::cli
