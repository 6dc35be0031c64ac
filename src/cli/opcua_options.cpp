#include "cli/opcua_options.hpp"

#include <iostream>

#include "proto/ads/plc/module_symbols.hpp"
#include "proto/net/endpoint.hpp"

namespace virtcom::cli {

void addOpcuaServeOptions(CLI::App* cmd, OpcuaServeOptions& o) {
  cmd->add_option("--opcua", o.listen,
                  "serve the PLC's variables over OPC UA (opc.tcp, security None, anonymous) on HOST:PORT, e.g. 127.0.0.1:4840 "
                  "(see docs/opcua.md); implies --speed 1");
  cmd->add_option("--opcua-allow", o.allow,
                  "comma-separated IPv4 addresses or networks (10.0.0.0/8) allowed to use --opcua (default: any; required beyond "
                  "loopback unless --allow-any-peer; docs/security.md)");
  cmd->add_flag("--opcua-readonly", o.readOnly, "refuse every OPC UA write (BadUserAccessDenied)");
  cmd->add_option("--opcua-max-sessions", o.maxSessions, "sessions open at once on --opcua (default 32)")->check(CLI::Range(1, 10000));
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
  std::cerr << "opcua: serving " << server.server().endpointUrl() << " (security None, anonymous)\n";
}

}  // namespace virtcom::cli
