#pragma once
// A loaded cell: the compiled PLC program, the devices, the tag bus, the wiring between device
// ports and PLC variables, the world (facts and zones) and the run settings.
// docs/cell-file.md describes the file format.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bytecode/module.hpp"
#include "cell/hmi_settings.hpp"
#include "core/ams_net_id.hpp"
#include "core/diagnostics.hpp"
#include "core/endpoint.hpp"
#include "core/modbus_map.hpp"
#include "core/production_plan.hpp"
#include "core/source.hpp"
#include "core/tag_bus.hpp"
#include "core/trace.hpp"
#include "lang/st/compiler.hpp"
#include "plant/device.hpp"
#include "plant/world.hpp"

namespace virtcom::cell {

// One device port connected to one PLC variable. Transfers are typed memory copies.
struct Wire {
  TagId tag = kNoTag;
  plant::PortDir dir = plant::PortDir::In;  // In: PLC variable -> tag; Out: tag -> PLC variable
  uint32_t address = 0;                     // in the PLC memory image
  int8_t bit = -1;
  ElemType varType = ElemType::Bool;        // storage type of the PLC variable
  std::string varName;                      // for messages
};

// A stop condition `NAME op VALUE` on a PLC variable, resolved at load time.
struct Condition {
  enum class Op { Eq, Ne, Lt, Le, Gt, Ge };
  std::string text;
  uint32_t address = 0;
  int8_t bit = -1;
  ElemType type = ElemType::Bool;
  Op op = Op::Eq;
  double value = 0;
  bool valid = false;
};

struct RunSettings {
  int64_t timeLimitNs = 600'000'000'000;  // 10 min of virtual time
  int64_t plcCycleNs = 10'000'000;        // default task interval
  Condition until;                        // stop when true (default: first completed cycle)
  std::string cycleDoneVar;               // BOOL PLC variable: each rising edge ends a cycle
  uint32_t cycles = 1;                    // stop after this many cycles (when cycleDoneVar is set)
  bool stopOnCollision = true;
  bool stopOnDeviceError = true;
  std::vector<std::string> recordVars;    // extra PLC variables recorded in the trace
  TagId cycleDoneTag = kNoTag;            // external PLC: the cycle_done variable as a BOOL tag
};

// `plc: modbus:` — the cell's controller is an external PLC, polled over Modbus TCP. Checked
// by the loader: the bridge takes the values as they are.
struct ModbusClientSettings {
  std::string address;                 // HOST:PORT as written (messages quote it)
  Endpoint peer;                       // the PLC's Modbus server (port never 0)
  int unit = 1;                        // unit id sent with every request
  int64_t pollNs = 10'000'000;         // read commands / write changed status this often
  int64_t timeoutNs = 500'000'000;     // a request unanswered this long means the link is lost
  bool faultOnLoss = true;             // on_loss: fault (end the run) or hold (keep, reconnect)
  modbus_map::SignalMap map;           // the PLC's tables (Client role); map.cycleDone: `cycle_done:`
};

// The signal `plc: modbus: cycle_done:` reads the external PLC's cycle marker into.
inline constexpr const char* kModbusCycleDoneSignal = "plc.cycle_done";

// A device port wired to a variable of an external PLC by name (`plc: ads:`): resolved, checked
// and given a handle when the bridge starts, since the program is not here to check it against.
struct ExternalWire {
  TagId tag = kNoTag;                       // kNoTag: a variable only recorded (`run: record`)
  plant::PortDir dir = plant::PortDir::In;  // In: PLC variable -> tag; Out: tag -> PLC variable
  std::string variable;                     // "MAIN.Robot1.execute"
  std::string port;                         // "Robot1.execute"; empty for a run variable
  SourceLocation loc;                       // the wiring entry (or run key) that names it
  bool optional = false;                    // wiring by prefix: skipped if the PLC lacks it
  int prefixGroup = -1;                     // wiring by prefix: one group per device; >= 1 must exist
};

// `plc: ads:` — the cell's controller is an external PLC reached over ADS (a TwinCAT runtime or
// `virtcom exec --ads`). Checked by the loader: the bridge takes the values as they are.
struct AdsClientSettings {
  std::string address;                 // HOST:PORT as written (messages quote it)
  Endpoint router;                     // its AMS router (TwinCAT: port 48898; port never 0)
  SourceLocation addressLoc;           // where connection problems are reported
  AmsNetId netId = kLocalAliasNetId;   // the target AmsNetId
  uint16_t port = 851;                 // the target AMS port (851 = PLC runtime 1)
  std::optional<AmsNetId> localNetId;  // our source AmsNetId; none: local IPv4 address + .1.1
  int64_t timeoutNs = 500'000'000;     // connect and each request
  bool faultOnLoss = true;             // on_loss: fault (end the run) or hold (keep, reconnect)
  bool disconnectWhenStopped = true;   // release the handles and disconnect when the run ends
  std::vector<ExternalWire> wires;     // the device wiring, then cycle_done and record
};

// A node named for a PLC variable in `plc: opcua: nodes:` (`MAIN.start: "ns=2;i=17"`).
struct OpcuaNodeName {
  std::string variable;  // "MAIN.start"
  std::string node;      // "ns=2;i=17" or a browse path "/4:MAIN/4:start", checked when the bridge starts
  SourceLocation loc;    // where the node is written: its problems are reported there
};

// `plc: opcua:` — the cell's controller is an external PLC reached over OPC UA (CODESYS, TwinCAT
// TF6100, a Siemens PLC, or `virtcom exec --opcua`). The wiring names PLC variables as with
// `plc: ads:`; each becomes the node `nodes:` gives it (a node id or a browse path), else
// node_prefix + the variable (a variable written as a node id, `ns=2;i=17`, is taken as it is).
// `security:` of `plc: opcua:`, with the values of OPC UA's MessageSecurityMode (OPC 10000-4
// §7.20); secured means security policy Basic256Sha256.
enum class OpcuaSecurity : uint32_t { None = 1, Sign = 2, SignAndEncrypt = 3 };

struct OpcuaClientSettings {
  std::string url;                     // "opc.tcp://127.0.0.1:4840" as written
  Endpoint server;                     // its host and port (port never 0)
  SourceLocation endpointLoc;          // where connection problems are reported
  OpcuaSecurity security = OpcuaSecurity::None;
  std::string pkiDir;                  // the bridge's PKI folder (relative: to the cell file's); empty: the default
  bool trustAnyServer = false;         // trust_server: any (else only the certificates of PKI/trusted/certs)
  std::string user, password;          // empty user: an anonymous session
  std::string nodePrefix = "ns=4;s=|var|virtcom.Application.";  // CODESYS' form, virtcom's device name
  std::vector<OpcuaNodeName> nodes;
  int64_t pollNs = 10'000'000;         // read commands / write changed status this often
  bool subscribe = true;               // commands by subscription (else, or if refused: a Read every poll)
  int64_t timeoutNs = 500'000'000;     // connect and each request
  bool faultOnLoss = true;             // on_loss: fault (end the run) or hold (keep, reconnect)
  bool disconnectWhenStopped = true;   // close the session and the channel when the run ends
  std::vector<ExternalWire> wires;     // the device wiring, then cycle_done and record
};

struct Cell {
  std::string name;
  std::filesystem::path file;
  std::unique_ptr<bc::Module> module;  // the soft PLC; null when the controller is external
  TagBus bus;
  Trace trace;
  plant::World world{trace};
  std::vector<std::unique_ptr<plant::Device>> devices;
  std::vector<ConfigNode> deviceEntries;  // each device's cell-file entry, in device order (mapping files resolved)
  std::vector<Wire> wires;
  RunSettings run;
  modbus_map::SignalMap modbus;        // what `virtcom serve --modbus` serves: `modbus:` or automatic
  std::optional<ModbusClientSettings> plcModbus;
  std::optional<AdsClientSettings> plcAds;
  std::optional<OpcuaClientSettings> plcOpcua;
  HmiSettings hmi;                     // `hmi:`: the HMI layout's placements and static shapes
  ProductionPlan plan;                 // `plan:`: shifts and their planned parts (virtcom monitor)

  // The wires of an external PLC whose variables the wiring names (`plc: ads:` or `plc: opcua:`);
  // null for the soft PLC, a Modbus PLC or none.
  std::vector<ExternalWire>* namedWires() {
    return plcAds ? &plcAds->wires : plcOpcua ? &plcOpcua->wires : nullptr;
  }
  // Whether the controller is an external PLC (`plc: modbus:`, `ads:` or `opcua:`).
  bool externalPlc() const { return plcModbus || plcAds || plcOpcua; }
};

// Every device port as a signal a protocol map can name ("Press.execute"), in device and port
// order; input ports are commands, output ports status.
std::vector<modbus_map::BusSignal> busSignals(const Cell& cell);

// Makes the controller external: drops the soft PLC and everything that names its variables
// (wiring, run conditions, recorded variables); the devices then take their commands from
// bridges only. Used by `virtcom serve`.
void detachSoftPlc(Cell& cell);

// Loads `path`: parses the YAML, compiles the PLC sources it names, creates the devices and the
// wiring and checks everything (unknown keys, units, PLC variables that do not exist or have an
// incompatible type, duplicate names). All problems are reported in one pass; returns null if
// there was any error. `sources` keeps the texts for rendering diagnostics.
// `plcOptions` are the PLC sources' compile options (e.g. coverage for `run --coverage`).
std::unique_ptr<Cell> loadCell(const std::string& path, SourceManager& sources, Diagnostics& diags,
                               st::CompileOptions plcOptions = {});

// A cell from a tree built in memory rather than read from a file (a scenario's `program:`, a
// PLC program alone: `root` holds only `plc:`), its relative paths read against `file`'s folder;
// built and checked as loadCell() does, diagnostics at the tree's own locations.
std::unique_ptr<Cell> loadCellTree(const std::filesystem::path& file, const ConfigNode& root, SourceManager& sources,
                                   Diagnostics& diags, st::CompileOptions plcOptions = {});

// The generic keys of a device's `faults:` entry (error_code, at_command, extra_delay,
// done_stuck, stuck_output) as a plan; at_command defaults to `defaultAtCommand` when an
// error_code is given (0: every command fails). Reports through `f`; shared by the cell file and
// scenario files (docs/scenarios.md), which change a plan in the middle of a run.
plant::FaultPlan readFaultPlan(ConfigReader& f, uint32_t defaultAtCommand);
// A device of `type` named `name` from its cell-file entry read by `cfg`: the entry's loader keys
// (wiring, faults, model, description) known, the rest read by the type's factory, unknown keys
// rejected; see plant::createDevice. Shared by the loader and scenario files, which build a device
// again from its entry with a value edited (a mid-run parameter change, docs/scenarios.md).
std::unique_ptr<plant::Device> createDeviceOfEntry(ConfigReader& cfg, const std::string& name, const std::string& type,
                                                   plant::World& world);
// A device's whole `faults:` entry into its plan, with its type's own keys (drives: `inject`,
// `comm_loss`); rejects unknown keys. The caller marks keys of its own (a scenario's `device`)
// read first.
void readDeviceFaults(plant::Device& d, ConfigReader& f);

// A cell file read and its soft PLC compiled once, for building many fresh cells from it
// without compiling again (`virtcom optimise` and `virtcom sweep`: one cell per candidate, its
// devices, world and bus in their initial state; docs/optimise.md).
struct CellTemplate {
  std::filesystem::path file;
  ConfigNode root;                     // the YAML tree, `extends` and `replace_devices` applied
  std::unique_ptr<bc::Module> module;  // the compiled soft PLC; null without one
};

// Reads, compiles and checks `path` as loadCell() does; null on any error.
std::unique_ptr<CellTemplate> loadCellTemplate(const std::string& path, SourceManager& sources, Diagnostics& diags);

// A fresh cell from `root` (the template's tree, or a copy with edited parameter values) with a
// copy of the template's compiled program: checked like a loaded file (mistakes in edited values
// are reported at their location), nothing compiled. Null on any error. Allocates; not for a
// scan path. Not thread-safe on `sources`/`diags`: one of each per thread.
std::unique_ptr<Cell> instantiateCell(const CellTemplate& tmpl, const ConfigNode& root, SourceManager& sources, Diagnostics& diags);

// Parses "MAIN.count >= 3" against the module (also used by `--until`). Reports through `diags`.
Condition parseCondition(const bc::Module& m, const std::string& text, SourceLocation loc, Diagnostics& diags);
bool evaluate(const Condition& c, const uint8_t* memory);

// A wire from a resolved variable (the transfers themselves: core/value_codec.hpp).
Wire makeWire(TagId tag, plant::PortDir dir, const bc::VarRef& ref, ElemType varType, std::string varName);

}  // namespace virtcom::cell
