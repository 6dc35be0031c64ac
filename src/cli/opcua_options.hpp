#pragma once
// The OPC UA server options (docs/opcua.md): `--opcua` and its limits on `exec` and `serve`, one definition
// of the flags, their checks, the binding to the scan loop and the announcement.
#include <expected>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "bytecode/module.hpp"
#include "core/tag_bus.hpp"
#include "cli/peer_options.hpp"
#include "plc/runtime.hpp"
#include "proto/ads/symbol_table.hpp"
#include "proto/opcua/server.hpp"

namespace virtcom::cell {
struct Cell;
}

namespace virtcom::cli {

struct OpcuaServeOptions {
  std::string flag = "--opcua";  // the option's name, the others' prefix (`monitor`: --serve-opcua)
  std::string listen;  // --opcua HOST:PORT; empty: no server
  std::string allow;   // --opcua-allow: IPv4 peers or networks; empty: any (loopback only)
  bool readOnly = false;
  size_t maxSessions = 32;
  std::string usersFile;  // --opcua-users FILE: accounts for UserName identities; empty: none
  std::string anonymous;  // --opcua-anonymous none|read|write; empty: read, or none with --opcua-users
  std::string security = "none";  // --opcua-security: comma list of none, sign, sign-encrypt
  std::string pkiDir;             // --opcua-pki DIR; empty: proto::opcua::defaultPkiDir()
  bool trustAnyClient = false;    // --opcua-trust-any-client: no trust list (tests, labs)
  bool enabled() const { return !listen.empty(); }
};

// The options named `flag`, `flag`-allow, `flag`-users, ...
void addOpcuaServeOptions(CLI::App* cmd, OpcuaServeOptions& o, const std::string& flag = "--opcua",
                          const std::string& listenHelp = "serve the PLC's variables over OPC UA (opc.tcp) on HOST:PORT, e.g. "
                                                          "127.0.0.1:4840 (see docs/opcua.md); implies --speed 1");

// The accounts of a users file (`--opcua-users`, `opcua-user add`); the error names the file
// (and line and column when its text is wrong: "users.txt:2:7: unknown role ..."). A missing file is empty when `missingIsEmpty`.
std::expected<std::vector<proto::opcua::UserAccount>, std::string> readOpcuaUsers(const std::string& path, bool missingIsEmpty = false);

// A compiled program served over OPC UA: its ADS symbol table (the address space is generated
// from it), serving a cell also its devices' signals, and the server; the scan loop calls
// afterScan() once after the cold start, then beforeScan()/afterScan() around every scan.
// Without a program (`monitor --serve-opcua`: the plant's PLC is elsewhere) only the devices'
// signals are served, published by publish() after every poll. None of them allocates.
class OpcuaPlcServer {
 public:
  void beforeScan(plc::Runtime& runtime, WriteObserver* audit = nullptr);
  void afterScan(plc::Runtime& runtime);
  // The devices' signals as the bus has them now, with `plcMemory` (empty without a program).
  void publish(std::span<const uint8_t> plcMemory);
  proto::opcua::Server& server() { return *server_; }
  void stop() { server_->stop(); }

 private:
  friend std::expected<std::unique_ptr<OpcuaPlcServer>, std::string> startOpcuaServer(const OpcuaServeOptions&, const PeerFlags&,
                                                                                      const bc::Module*, const cell::Cell*);
  // A device signal in the image's extra part: 8 bytes per signal, in serving order.
  struct DeviceSignal {
    TagId tag;
    bool asFloat;  // a REAL: the bus holds a double, OPC UA serves a Float
  };
  explicit OpcuaPlcServer(proto::ads::SymbolTable table) : table_(std::move(table)) {}
  proto::opcua::AddressSpaceConfig deviceNodes(const cell::Cell& cell);
  proto::ads::SymbolTable table_;
  const TagBus* bus_ = nullptr;
  std::vector<DeviceSignal> signals_;
  std::vector<uint8_t> deviceImage_;
  std::unique_ptr<proto::opcua::Server> server_;
};

// Checks the options and starts the server over `module` (which must outlive it; null: no
// program) and, when `cell` is given (`serve`, `monitor`), its devices' signals read only in
// Objects/Devices (which must outlive it too). The error text names the option at fault
// ("--opcua: ...").
std::expected<std::unique_ptr<OpcuaPlcServer>, std::string> startOpcuaServer(const OpcuaServeOptions& o, const PeerFlags& peers,
                                                                              const bc::Module* module, const cell::Cell* cell = nullptr);

// "opcua: serving opc.tcp://127.0.0.1:4840 (security None, anonymous read-only)" on stderr (the
// identities accepted: "anonymous read-only", "2 users", ...), once the
// first image is published (e2e tests and scripts wait for it).
void announceOpcuaServer(OpcuaPlcServer& server);

}  // namespace virtcom::cli
