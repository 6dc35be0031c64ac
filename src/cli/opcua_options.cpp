#include "cli/opcua_options.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "cell/cell.hpp"
#include "proto/ads/plc/module_symbols.hpp"
#include "proto/net/endpoint.hpp"
#include "proto/opcua/crypto.hpp"

namespace virtcom::cli {

void addOpcuaServeOptions(CLI::App* cmd, OpcuaServeOptions& o, const std::string& flag, const std::string& listenHelp) {
  o.flag = flag;
  cmd->add_option(flag, o.listen, listenHelp);
  cmd->add_option(flag + "-allow", o.allow,
                  "comma-separated IPv4 addresses or networks (10.0.0.0/8) allowed to use " + flag + " (default: any; required beyond "
                  "loopback unless --allow-any-peer; docs/security.md)");
  cmd->add_flag(flag + "-readonly", o.readOnly, "refuse every OPC UA write (BadUserAccessDenied)");
  cmd->add_option(flag + "-max-sessions", o.maxSessions, "sessions open at once on " + flag + " (default 32)")->check(CLI::Range(1, 10000));
  cmd->add_option(flag + "-users", o.usersFile,
                  "users file: user names, roles (read-only, read-write) and password hashes for OPC UA UserName identities; "
                  "create entries with `virtcom opcua-user add` (docs/opcua.md, Users and roles)")
      ->check(CLI::ExistingFile);
  cmd->add_option(flag + "-anonymous", o.anonymous,
                  "what an anonymous OPC UA session may do: none (refused), read (browse, read, subscribe) or write (default: read, "
                  "or none with " + flag + "-users)")
      ->check(CLI::IsMember({"none", "read", "write"}));
  cmd->add_option(flag + "-security", o.security,
                  "the OPC UA endpoints, a comma list of none, sign and sign-encrypt (Basic256Sha256 for the last two; default: "
                  "none; docs/opcua.md, Security)");
  cmd->add_option(flag + "-pki", o.pkiDir,
                  "the OPC UA PKI folder: the server certificate (generated at first start), trusted/certs, rejected/certs "
                  "(default: $XDG_DATA_HOME/virtcom/opcua-pki or ~/.local/share/virtcom/opcua-pki)");
  cmd->add_flag(flag + "-trust-any-client", o.trustAnyClient,
                "accept any valid client certificate on the secured endpoints, without the trust list (tests and labs only)");
}

namespace {

// The modes of --opcua-security, in the order given, each once.
std::expected<std::vector<proto::opcua::SecurityMode>, std::string> parseSecurityModes(const OpcuaServeOptions& o) {
  using proto::opcua::SecurityMode;
  static const std::map<std::string, SecurityMode> kModes{
      {"none", SecurityMode::None}, {"sign", SecurityMode::Sign}, {"sign-encrypt", SecurityMode::SignAndEncrypt}};
  std::vector<SecurityMode> modes;
  std::stringstream words(o.security);
  for (std::string word; std::getline(words, word, ',');) {
    auto it = kModes.find(word);
    if (it == kModes.end())
      return std::unexpected(o.flag + "-security: unknown mode '" + word + "'; expected a comma list of none, sign, sign-encrypt");
    if (std::ranges::find(modes, it->second) == modes.end()) modes.push_back(it->second);
  }
  if (modes.empty()) return std::unexpected(o.flag + "-security: empty; expected a comma list of none, sign, sign-encrypt");
  return modes;
}

// The modes and, when one is secured, the PKI folder (its certificate generated at first start).
std::expected<void, std::string> configureSecurity(const OpcuaServeOptions& o, proto::opcua::ServerConfig& config) {
  namespace ua = proto::opcua;
  auto modes = parseSecurityModes(o);
  if (!modes) return std::unexpected(modes.error());
  config.securityModes = std::move(*modes);
  if (std::ranges::all_of(config.securityModes, [](ua::SecurityMode m) { return m == ua::SecurityMode::None; })) return {};
  if (auto crypto = ua::loadCrypto(); !crypto) return std::unexpected(o.flag + "-security: the security policy needs " + crypto.error());
  auto pki = ua::openPki(o.pkiDir.empty() ? ua::defaultPkiDir() : o.pkiDir, config.names.applicationUri);
  if (!pki) return std::unexpected(o.flag + "-pki: " + pki.error());
  pki->trustAny = o.trustAnyClient;
  config.pki = std::make_shared<const ua::Pki>(std::move(*pki));
  return {};
}

}  // namespace

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

// Every port of every device whose type OPC UA serves (not STRING), one 8-byte slot each.
proto::opcua::AddressSpaceConfig OpcuaPlcServer::deviceNodes(const cell::Cell& cell) {
  namespace ua = proto::opcua;
  ua::AddressSpaceConfig names;
  bus_ = &cell.bus;
  for (const auto& device : cell.devices) {
    ua::ExtraObject object{device->name(), {}};
    for (size_t i = 0; i < device->ports().size(); ++i) {
      const plant::PortSpec& port = device->ports()[i];
      const ua::BuiltinType type = ua::builtinOf(proto::ads::adsTypeOf(port.type));
      if (type == ua::BuiltinType::Null || type == ua::BuiltinType::String) continue;
      const auto slot = static_cast<uint32_t>(signals_.size());
      object.variables.push_back({port.name, type, slot * 8, elemTypeInfo(port.type).sizeBytes});
      signals_.push_back({device->tag(i), port.type == ElemType::Real});
    }
    names.devices.push_back(std::move(object));
  }
  names.extraBytes = static_cast<uint32_t>(signals_.size() * 8);
  deviceImage_.assign(names.extraBytes, 0);
  return names;
}

std::expected<std::unique_ptr<OpcuaPlcServer>, std::string> startOpcuaServer(const OpcuaServeOptions& o, const PeerFlags& peers,
                                                                              const bc::Module* module, const cell::Cell* cell) {
  namespace ua = proto::opcua;
  auto endpoint = proto::net::parseEndpoint(o.listen);
  if (!endpoint) return std::unexpected(o.flag + ": " + endpoint.error());
  ua::ServerConfig config;
  config.listen = *endpoint;
  config.readOnly = o.readOnly;
  config.maxSessions = o.maxSessions;
  if (!o.usersFile.empty()) {
    auto users = readOpcuaUsers(o.usersFile);
    if (!users) return std::unexpected(o.flag + "-users: " + users.error());
    if (users->empty()) return std::unexpected(o.flag + "-users: " + o.usersFile + " lists no user (add one with `virtcom opcua-user add`)");
    if (auto crypto = ua::loadCrypto(); !crypto) return std::unexpected(o.flag + "-users: the password checks need " + crypto.error());
    config.users = std::move(*users);
    config.anonymous = ua::UserAccess::None;
  }
  static const std::map<std::string, ua::UserAccess> kAnonymous{
      {"none", ua::UserAccess::None}, {"read", ua::UserAccess::Read}, {"write", ua::UserAccess::Write}};
  if (!o.anonymous.empty()) config.anonymous = kAnonymous.at(o.anonymous);
  if (config.anonymous == ua::UserAccess::None && config.users.empty())
    return std::unexpected(o.flag + "-anonymous none: nobody could log on; give " + o.flag + "-users FILE too");
  auto policy = peerPolicy(*endpoint, peers, "opcua", o.flag, o.flag + "-allow", o.allow);
  if (!policy) return std::unexpected(policy.error());
  config.peers = std::move(*policy);
  std::unique_ptr<OpcuaPlcServer> s(new OpcuaPlcServer(module ? proto::ads::buildSymbolTable(*module) : proto::ads::SymbolTable({}, {}, {}, nullptr)));
  if (cell) config.names = s->deviceNodes(*cell);
  if (auto secured = configureSecurity(o, config); !secured) return std::unexpected(secured.error());
  auto server = ua::Server::start(config, s->table_);
  if (!server) return std::unexpected(o.flag + ": " + server.error());
  s->server_ = std::move(*server);
  return s;
}

void OpcuaPlcServer::beforeScan(plc::Runtime& runtime, WriteObserver* audit) {
  const bc::Module& m = runtime.module();
  proto::opcua::LiveImage live{{runtime.machine().memory(), m.staticSize}, {runtime.inputImage(), m.inputs.size}};
  if (server_->applyPendingWrites(live, audit) > 0) runtime.inputsTouched();
}

void OpcuaPlcServer::afterScan(plc::Runtime& runtime) { publish({runtime.machine().memory(), runtime.module().staticSize}); }

void OpcuaPlcServer::publish(std::span<const uint8_t> plcMemory) {
  for (size_t k = 0; k < signals_.size(); ++k) {
    uint64_t raw = bus_->raw(signals_[k].tag);  // little endian: a narrower type is its low bytes
    if (signals_[k].asFloat) raw = std::bit_cast<uint32_t>(static_cast<float>(std::bit_cast<double>(raw)));
    std::memcpy(deviceImage_.data() + k * 8, &raw, 8);
  }
  server_->publishSnapshot(plcMemory, deviceImage_);
}

void announceOpcuaServer(OpcuaPlcServer& server) {
  const proto::opcua::ServerConfig& c = server.server().config();
  std::string identities;
  if (c.anonymous != proto::opcua::UserAccess::None)
    identities = std::string("anonymous ") + (c.anonymous == proto::opcua::UserAccess::Write ? "read-write" : "read-only");
  if (!c.users.empty())
    identities += (identities.empty() ? "" : ", ") + std::to_string(c.users.size()) + (c.users.size() == 1 ? " user" : " users");
  // One write: tests and scripts wait for the whole line.
  static constexpr const char* kModeNames[] = {"", "None", "Basic256Sha256 Sign", "Basic256Sha256 SignAndEncrypt"};
  std::string security;
  for (proto::opcua::SecurityMode m : c.securityModes) security += std::string(kModeNames[static_cast<size_t>(m)]) + ", ";
  std::string pki = c.pki ? "PKI " + c.pki->dir + (c.pki->trustAny ? " (any client trusted)" : "") + ", " : "";
  std::cerr << "opcua: serving " + server.server().endpointUrl() + " (security " + security + pki + identities + ")\n";
}

}  // namespace virtcom::cli
