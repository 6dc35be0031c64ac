// Loading a cell file: YAML -> checked Cell with compiled PLC program, devices and wiring.
#include <algorithm>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include "cell/ads_settings.hpp"
#include "cell/opcua_settings.hpp"
#include "cell/cell.hpp"
#include "cell/hmi_section.hpp"
#include "cell/plan_section.hpp"
#include "cell/mapping_file.hpp"
#include "cell/modbus_settings.hpp"
#include "cell/yaml_config.hpp"
#include "core/cell_diagnostic_codes.hpp"
#include "core/value_codec.hpp"
#include "drives/drive_registry.hpp"
#include "lang/plcopen/importer.hpp"
#include "lang/st/compiler.hpp"

namespace virtcom::cell {

namespace {

bool readText(const std::filesystem::path& p, std::string& out) {
  std::ifstream in(p, std::ios::binary);
  if (!in) return false;
  std::stringstream ss;
  ss << in.rdbuf();
  out = ss.str();
  return true;
}

bool compatible(ElemType port, const bc::TypeDesc& var) {
  if (var.kind != bc::TypeKind::Elementary && var.kind != bc::TypeKind::Enum) return false;
  return wireCompatible(port, var.elem, var.kind == bc::TypeKind::Enum);
}

const char* dirText(plant::PortDir d) { return d == plant::PortDir::In ? "input" : "output"; }

class Loader {
 public:
  // `precompiled`: the soft PLC to copy instead of compiling the files `plc: sources` names.
  Loader(SourceManager& sources, Diagnostics& diags, st::CompileOptions plcOptions = {}, const bc::Module* precompiled = nullptr)
      : sources_(sources), diags_(diags), plcOptions_(plcOptions), precompiled_(precompiled) {}

  // The file's YAML tree with `extends` / `replace_devices` applied; false on an error.
  bool readTree(const std::string& path, ConfigNode& root) {
    std::string text;
    if (!readText(path, text)) {
      diags_.error(celldiag::C002, {}, "cannot read cell file '" + path + "'");
      return false;
    }
    return parseYaml(path, text, sources_, diags_, root) && takeBaseSections(path, root);
  }

  std::unique_ptr<Cell> load(const std::string& path) {
    ConfigNode root;
    if (!readTree(path, root)) return nullptr;
    return build(path, root);
  }

  // The cell described by `root` (a tree from readTree(), possibly edited), read from `path`.
  std::unique_ptr<Cell> build(const std::filesystem::path& path, const ConfigNode& root) {
    auto cell = std::make_unique<Cell>();
    cell->file = path;
    ConfigReader top(root, diags_, "the cell file");
    cell->name = top.optString("name", path.parent_path().filename().string());
    // Every part is checked even when an earlier one failed, so one run reports all mistakes;
    // without a compiled PLC program the run settings and wiring cannot be checked.
    bool plcOk = compilePlc(*cell, top);
    plcBroken_ = !plcOk;
    if (plcOk || cell->namedWires()) readRun(*cell, top);
    else top.child("run");  // known key; its conditions need the compiled program
    readWorld(*cell, top);
    readDevices(*cell, top);
    // Maps name device signals, so they are read once the devices exist.
    readModbusSection(*cell, top.child("modbus"), diags_);
    if (plcModbus_) readModbusClient(*cell, *plcModbus_, diags_);
    readHmiSection(*cell, top.child("hmi"), diags_);  // names devices
    readPlanSection(*cell, top.child("plan"), diags_);
    top.child("extends");          // applied by takeBaseSections()
    top.child("replace_devices");  // applied by takeBaseSections()
    if (plcAds_) readAdsClient(*cell->plcAds, *plcAds_, diags_);
    if (cell->plcOpcua) readOpcuaClient(*cell->plcOpcua, *plcOpcua_, cell->file.parent_path(), diags_);
    if (cell->namedWires()) addExternalRunWires(*cell);
    top.rejectUnknownKeys();
    if (diags_.hasErrors()) return nullptr;
    return cell;
  }

  // The file ids [first, second) of the soft PLC's sources (empty without one).
  std::pair<uint32_t, uint32_t> plcFiles() const { return plcFiles_; }

 private:
  // `extends: other.yaml` (relative to this file): every top-level section of that cell file
  // which this one does not have is taken as written there, so variants of a cell (another
  // PLC program, other run settings) need not repeat its devices. One level only: the base
  // must not extend another file. Paths inside taken sections stay relative to this file.
  // `replace_devices:` swaps single devices of the base's list (replacedDevices()).
  bool takeBaseSections(const std::filesystem::path& path, ConfigNode& root) {
    const ConfigNode* ext = root.kind() == ConfigNode::Kind::Map ? root.find("extends") : nullptr;
    const ConfigNode* replacements = root.kind() == ConfigNode::Kind::Map ? root.find("replace_devices") : nullptr;
    if (replacements && !ext)
      diags_.error(celldiag::C010, root.keyLoc("replace_devices"),
                   "'replace_devices' replaces devices of the cell file named by 'extends', but this file has no 'extends'");
    if (replacements && root.has("devices"))
      diags_.error(celldiag::C010, root.keyLoc("replace_devices"),
                   "'replace_devices' replaces devices of the base file, but this file has its own 'devices'");
    if (!ext) return true;
    std::filesystem::path basePath = (path.parent_path() / ext->scalar()).lexically_normal();
    std::string text;
    if (ext->kind() != ConfigNode::Kind::Scalar || !readText(basePath, text)) {
      diags_.error(celldiag::C002, ext->loc(), "cannot read cell file '" + basePath.string() + "' named by 'extends'");
      return false;
    }
    ConfigNode base;
    if (!parseYaml(basePath.string(), text, sources_, diags_, base)) return false;
    if (base.find("extends")) {
      diags_.error(celldiag::C010, base.keyLoc("extends"), "a cell file named by 'extends' cannot itself extend another file");
      return false;
    }
    // built before root grows: `replacements` points into root
    const ConfigNode* baseDevices = base.find("devices");
    std::optional<ConfigNode> devices;
    if (replacements && baseDevices && !root.has("devices")) devices = replacedDevices(*baseDevices, *replacements);
    for (const auto& [key, value] : base.entries())
      if (!root.has(key)) root.add(key, base.keyLoc(key), key == "devices" && devices ? *devices : value);
    return true;
  }

  // The base's `devices` list with the variant's `replace_devices` entries in place of the
  // devices of the same name (the list keeps its order: devices step in file order), so a
  // variant that swaps one device (the ideal table axes for drives) need not repeat the others.
  ConfigNode replacedDevices(const ConfigNode& devices, const ConfigNode& replacements) {
    if (devices.kind() != ConfigNode::Kind::List) return devices;  // readDevices() reports it
    if (replacements.kind() != ConfigNode::Kind::List) {
      diags_.error(celldiag::C010, replacements.loc(), "'replace_devices' must be a list of devices, each named like a device of the base file");
      return devices;
    }
    std::vector<const ConfigNode*> chosen;
    for (const ConfigNode& d : devices.items()) chosen.push_back(&d);
    for (const ConfigNode& r : replacements.items()) {
      const ConfigNode* name = r.kind() == ConfigNode::Kind::Map ? r.find("name") : nullptr;
      auto same = [&](const ConfigNode& d) {
        const ConfigNode* n = d.kind() == ConfigNode::Kind::Map ? d.find("name") : nullptr;
        return name && n && n->scalar() == name->scalar();
      };
      const auto it = std::find_if(devices.items().begin(), devices.items().end(), same);
      const size_t at = static_cast<size_t>(it - devices.items().begin());
      if (it == devices.items().end())
        diags_.error(celldiag::C010, name ? name->loc() : r.loc(),
                     name ? "'replace_devices': the base file has no device '" + name->scalar() + "' to replace"
                          : std::string("'replace_devices': every entry needs the 'name' of the base file's device it replaces"));
      else if (chosen[at] != &*it)
        diags_.error(celldiag::C010, name->loc(), "'replace_devices': device '" + name->scalar() + "' is replaced twice");
      else
        chosen[at] = &r;
    }
    ConfigNode out = ConfigNode::makeList(devices.loc());
    for (const ConfigNode* d : chosen) out.push(*d);
    return out;
  }

  // True unless there was an error. Without `plc:` or its `sources:` the cell has no controller
  // of its own (it can only be served); `plc: modbus:` makes an external PLC the controller.
  bool compilePlc(Cell& cell, ConfigReader& top) {
    const ConfigNode* plcNode = top.child("plc");
    if (!plcNode) return true;
    ConfigReader plc(*plcNode, diags_, "'plc'");
    std::vector<st::SourceInput> inputs;
    const ConfigNode* srcs = plc.child("sources");
    plcModbus_ = plcNode->find("modbus");
    plcAds_ = plcNode->find("ads");
    plcOpcua_ = plcNode->find("opcua");
    // The external PLC sections given (one at most may be).
    const std::pair<const char*, const ConfigNode*> externals[] = {{"modbus", plcModbus_}, {"ads", plcAds_}, {"opcua", plcOpcua_}};
    std::vector<std::pair<const char*, const ConfigNode*>> given;
    for (const auto& e : externals)
      if (e.second) given.push_back(e);
    if (plcAds_) cell.plcAds.emplace();
    else if (plcOpcua_) cell.plcOpcua.emplace();
    if (srcs && !given.empty()) {
      plc.error(given[0].second->loc(), std::string("'plc' has either 'sources' (the soft PLC) or '") + given[0].first +
                                            "' (an external PLC), not both");
    } else if (given.size() > 1) {
      plc.error(given[1].second->loc(), std::string("'plc' has either '") + given[0].first + "' or '" + given[1].first +
                                            "' (one external PLC), not both");
    } else if (!given.empty() || !srcs) {
      // no soft PLC; `plc: modbus:`, `ads:` and `opcua:` are read with the devices' signals, see load()
    } else if (srcs->kind() != ConfigNode::Kind::List || srcs->items().empty()) {
      plc.error(srcs->loc(), "'sources' must be a list of ST (.st), PLCopen XML (.xml) or TwinCAT 3 (.TcPOU, .TcGVL, .TcDUT, .TcIO) files relative to the cell file");
    } else if (!precompiled_) {
      for (const auto& item : srcs->items()) {
        std::filesystem::path p = cell.file.parent_path() / item.scalar();
        std::string st;
        if (!readText(p, st)) {
          plc.error(item.loc(), "cannot read PLC source '" + p.string() + "'");
          continue;
        }
        inputs.push_back(plcopen::sourceInput(p.lexically_normal().string(), std::move(st)));
      }
    }
    cell.run.plcCycleNs = static_cast<int64_t>(plc.optQuantity("cycle_time", Dimension::Time, 0.01) * 1e9 + 0.5);
    if (plc.ok() && cell.run.plcCycleNs < 1000)
      plc.error(plc.node().find("cycle_time") ? plc.node().find("cycle_time")->loc() : plcNode->loc(),
                "'cycle_time' must be at least 1 us");
    plc.child("modbus");
    plc.child("ads");
    plc.child("opcua");
    plc.rejectUnknownKeys();
    if (diags_.hasErrors()) return false;
    if (precompiled_ && srcs && given.empty()) {
      cell.module = std::make_unique<bc::Module>(*precompiled_);  // a copy of the image, no compile
    } else {
      if (inputs.empty()) return true;
      plcFiles_.first = static_cast<uint32_t>(sources_.fileCount());
      cell.module = st::compileProgram(inputs, sources_, diags_, plcOptions_);
      plcFiles_.second = static_cast<uint32_t>(sources_.fileCount());
    }
    if (!cell.module) return false;
    for (auto& t : cell.module->tasks)
      if (t.isDefault) t.intervalNs = cell.run.plcCycleNs;
    return true;
  }

  void readRun(Cell& cell, ConfigReader& top) {
    const ConfigNode* runNode = top.child("run");
    if (!runNode) return;
    ConfigReader run(*runNode, diags_, "'run'");
    RunSettings& r = cell.run;
    r.timeLimitNs = static_cast<int64_t>(run.optQuantity("time_limit", Dimension::Time, 600.0) * 1e9 + 0.5);
    if (r.timeLimitNs <= 0) run.error(runNode->find("time_limit")->loc(), "'time_limit' must be positive");
    // Keys are read in this order so that unknown-key messages list them so.
    readRunVariables(cell, run, {"until", "cycle_done"});
    int64_t cycles = run.optInt("cycles", 1);
    if (cycles < 1 || cycles > 1'000'000) run.error(runNode->find("cycles")->loc(), "'cycles' must be 1..1000000");
    r.cycles = static_cast<uint32_t>(std::clamp<int64_t>(cycles, 1, 1'000'000));
    r.stopOnCollision = run.optBool("stop_on_collision", true);
    r.stopOnDeviceError = run.optBool("stop_on_device_error", true);
    readRunVariables(cell, run, {"record"});
    run.rejectUnknownKeys();
  }

  // The run settings among `keys` that name PLC variables: resolved in the soft PLC, or (with
  // `plc: ads:`) named for the bridge to resolve; refused with no PLC that has variables.
  void readRunVariables(Cell& cell, ConfigReader& run, std::initializer_list<std::string> keys) {
    for (const std::string& key : keys) {
      const ConfigNode* n = run.child(key);
      if (!n) continue;
      if (cell.namedWires()) readExternalRunVariable(cell, run, key, *n);
      else if (!cell.module) run.error(n->loc(), "'" + key + "' names PLC variables, but the cell has no soft PLC ('plc: sources')");
      else if (key == "until") cell.run.until = parseCondition(*cell.module, n->scalar(), n->loc(), diags_);
      else if (key == "cycle_done") readCycleDone(cell, run, *n);
      else readRecord(cell, run, *n);
    }
  }

  // `cycle_done` and `record` of a cell whose PLC is reached over ADS: kept by name (tags and
  // wires are added once the devices have theirs, see addExternalRunWires).
  void readExternalRunVariable(const Cell& cell, ConfigReader& run, const std::string& key, const ConfigNode& n) {
    if (key == "until") {
      run.error(n.loc(), std::string("'until' needs the soft PLC ('plc: sources'); with 'plc: ") + (cell.plcAds ? "ads" : "opcua") +
                             "' end the run with 'cycle_done' or 'time_limit'");
    } else if (key == "cycle_done") {
      if (n.kind() != ConfigNode::Kind::Scalar || n.scalar().empty()) run.error(n.loc(), "'cycle_done' must name a BOOL PLC variable");
      else externalRun_.push_back({n.scalar(), n.loc(), true});
    } else if (n.kind() != ConfigNode::Kind::List) {
      run.error(n.loc(), "'record' must be a list of PLC variables");
    } else {
      for (const auto& item : n.items()) externalRun_.push_back({item.scalar(), item.loc(), false});
    }
  }

  void addExternalRunWires(Cell& cell) {
    for (const ExternalRunVariable& v : externalRun_) {
      ExternalWire w;
      w.variable = v.name;
      w.loc = v.loc;
      if (v.cycleDone) {
        // A BOOL tag the bridge reads every step; the simulation counts its rising edges.
        TagId tag = cell.bus.find(v.name);
        w.tag = tag != kNoTag ? tag : cell.bus.add(v.name, ElemType::Bool);
        cell.run.cycleDoneTag = w.tag;
      }
      cell.namedWires()->push_back(std::move(w));
    }
  }

  void readCycleDone(Cell& cell, ConfigReader& run, const ConfigNode& c) {
    RunSettings& r = cell.run;
    r.cycleDoneVar = c.scalar();
    auto ref = bc::resolveVariable(*cell.module, r.cycleDoneVar);
    if (!ref || cell.module->types[ref->type].elem != ElemType::Bool || cell.module->types[ref->type].kind != bc::TypeKind::Elementary)
      run.error(c.loc(), "'cycle_done' must name a BOOL PLC variable; '" + r.cycleDoneVar + "' is not one");
  }

  void readRecord(Cell& cell, ConfigReader& run, const ConfigNode& rec) {
    RunSettings& r = cell.run;
    for (const auto& item : rec.items()) {
      auto ref = bc::resolveVariable(*cell.module, item.scalar());
      if (!ref) {
        run.error(item.loc(), "'record': no PLC variable '" + item.scalar() + "'");
        continue;
      }
      const bc::TypeDesc& t = cell.module->types[ref->type];
      if (t.kind != bc::TypeKind::Elementary && t.kind != bc::TypeKind::Enum) {
        run.error(item.loc(), "'record': '" + item.scalar() + "' is a " + t.name + "; record its elementary members instead");
        continue;
      }
      // a variable listed twice is recorded once
      if (std::find(r.recordVars.begin(), r.recordVars.end(), item.scalar()) == r.recordVars.end()) r.recordVars.push_back(item.scalar());
    }
  }

  void readWorld(Cell& cell, ConfigReader& top) {
    if (const ConfigNode* zones = top.child("zones"))
      for (const auto& z : zones->items()) cell.world.zone(z.scalar());
    const ConfigNode* worldNode = top.child("world");
    if (!worldNode) return;
    ConfigReader world(*worldNode, diags_, "'world'");
    if (const ConfigNode* facts = world.child("facts")) {
      if (facts->kind() != ConfigNode::Kind::Map) {
        world.error(facts->loc(), "'facts' must map fact names to true/false");
      } else {
        ConfigReader f(*facts, diags_, "'facts'");
        for (const auto& [name, value] : facts->entries()) cell.world.setInitial(cell.world.fact(name), f.optBool(name, false));
      }
    }
    world.rejectUnknownKeys();
  }

  void readDevices(Cell& cell, ConfigReader& top) {
    const ConfigNode* list = top.child("devices");
    if (!list || list->kind() != ConfigNode::Kind::List) {
      top.error(list ? list->loc() : top.node().loc(), "the cell file needs 'devices:', a list of devices");
      return;
    }
    std::set<std::string> names;
    for (const auto& entry : list->items()) {
      const ConfigNode node = resolveMappingFile(entry, cell.file.parent_path(), sources_, diags_);
      ConfigReader cfg(node, diags_, "device");
      std::string name = cfg.requireString("name");
      std::string type = cfg.requireString("type");
      if (name.empty() || type.empty()) continue;
      if (!names.insert(name).second) {
        cfg.error(node.loc(), "a device named '" + name + "' already exists");
        continue;
      }
      // an entry with parameter mistakes still yields its device, so its wiring and signals are
      // checked in the same run (load() then fails, so such a device never runs)
      auto device = createDeviceOfEntry(cfg, name, type, cell.world);
      if (!device) continue;  // unknown type
      if (const ConfigNode* faults = cfg.child("faults")) readFaults(*device, *faults);
      bindPorts(cell, *device, cfg.child("wiring"), node);
      cell.devices.push_back(std::move(device));
      cell.deviceEntries.push_back(node);
    }
    reportUndefinedVessels(cell);
  }

  // A valve, pump, heater or tank sensor names a tank no device entry defines.
  void reportUndefinedVessels(Cell& cell) {
    std::vector<uint32_t> undefined = cell.world.undefinedVessels();
    if (undefined.empty()) return;
    std::string tanks;
    for (const auto& d : cell.devices)
      if (d->type() == "tank") tanks += (tanks.empty() ? "" : ", ") + d->name();
    for (uint32_t id : undefined) {
      const plant::Vessel& v = cell.world.vesselAt(id);
      diags_.error(celldiag::C010, v.firstUse,
                   "no tank named '" + v.name + "' (expected the name of a device of type tank; the cell has " +
                       (tanks.empty() ? "none" : tanks) + ")");
    }
  }

  void readFaults(plant::Device& d, const ConfigNode& node) {
    ConfigReader f(node, diags_, "'faults'");
    readDeviceFaults(d, f);
  }

  void bindPorts(Cell& cell, plant::Device& d, const ConfigNode* wiring, const ConfigNode& deviceNode) {
    const auto& ports = d.ports();
    for (size_t i = 0; i < ports.size(); ++i) d.bindPort(i, cell.bus.add(d.name() + "." + ports[i].name, ports[i].type));
    if (!wiring) return;  // an unwired device still simulates (e.g. driven only by faults, facts or a bridge)
    if (std::vector<ExternalWire>* wires = cell.namedWires()) {
      bindExternal(*wires, d, *wiring, static_cast<int>(cell.devices.size()));
      return;
    }
    if (!cell.module) {
      // A soft PLC that failed to compile has been reported; one "no soft PLC" per wired device
      // would only bury its errors.
      if (plcBroken_) return;
      diags_.error(celldiag::C030, wiring->loc(), "'wiring' connects ports to PLC variables, but the cell has no soft PLC ('plc: sources') "
                                          "and no ADS or OPC UA PLC ('plc: ads', 'plc: opcua'); a Modbus PLC reaches the signals through its map");
      return;
    }
    if (wiring->kind() == ConfigNode::Kind::Scalar) {
      // Prefix form: every port P is wired to PREFIX.P if that PLC variable exists.
      size_t wired = 0;
      for (size_t i = 0; i < ports.size(); ++i) {
        std::string var = wiring->scalar() + "." + ports[i].name;
        if (!bc::resolveVariable(*cell.module, var)) continue;
        wired += connect(cell, d, i, var, wiring->loc());
      }
      if (wired == 0)
        diags_.error(celldiag::C030, wiring->loc(), "no port of '" + d.name() + "' matches a variable under '" + wiring->scalar() +
                                                 "' (expected e.g. " + wiring->scalar() + "." + (ports.empty() ? "execute" : ports[0].name) + ")");
      return;
    }
    if (wiring->kind() != ConfigNode::Kind::Map) {
      diags_.error(celldiag::C030, wiring->loc(), "'wiring' must be a PLC variable prefix (MAIN.Robot1) or a map port: variable");
      return;
    }
    for (const auto& [port, var] : wiring->entries()) {
      int index = d.portIndex(port);
      if (index < 0) {
        std::string known;
        for (const auto& p : ports) known += (known.empty() ? "" : ", ") + p.name;
        diags_.error(celldiag::C031, wiring->keyLoc(port), "device '" + d.name() + "' has no port '" + port + "' (ports: " + known + ")");
        continue;
      }
      if (!bc::resolveVariable(*cell.module, var.scalar())) {
        diags_.error(celldiag::C032, var.loc(), "the PLC has no variable '" + var.scalar() + "' to wire to " + d.name() + "." + port);
        continue;
      }
      connect(cell, d, static_cast<size_t>(index), var.scalar(), var.loc());
    }
    (void)deviceNode;
  }

  // Wiring to an external PLC's variables by name: checked against the PLC when the bridge
  // starts. The prefix form wires every port to PREFIX.port where the PLC has that variable.
  void bindExternal(std::vector<ExternalWire>& wires, plant::Device& d, const ConfigNode& wiring, int deviceIndex) {
    const auto& ports = d.ports();
    auto wire = [&](size_t i, std::string var, SourceLocation loc, bool optional) {
      ExternalWire w;
      w.tag = d.tag(i);
      w.dir = ports[i].dir;
      w.variable = std::move(var);
      w.port = d.name() + "." + ports[i].name;
      w.loc = loc;
      w.optional = optional;
      w.prefixGroup = optional ? deviceIndex : -1;
      wires.push_back(std::move(w));
    };
    if (wiring.kind() == ConfigNode::Kind::Scalar) {
      for (size_t i = 0; i < ports.size(); ++i) wire(i, wiring.scalar() + "." + ports[i].name, wiring.loc(), true);
      return;
    }
    if (wiring.kind() != ConfigNode::Kind::Map) {
      diags_.error(celldiag::C030, wiring.loc(), "'wiring' must be a PLC variable prefix (MAIN.Robot1) or a map port: variable");
      return;
    }
    for (const auto& [port, var] : wiring.entries()) {
      int index = d.portIndex(port);
      if (index < 0) {
        std::string known;
        for (const auto& p : ports) known += (known.empty() ? "" : ", ") + p.name;
        diags_.error(celldiag::C031, wiring.keyLoc(port), "device '" + d.name() + "' has no port '" + port + "' (ports: " + known + ")");
        continue;
      }
      wire(static_cast<size_t>(index), var.scalar(), var.loc(), false);
    }
  }

  size_t connect(Cell& cell, plant::Device& d, size_t port, const std::string& var, SourceLocation loc) {
    const plant::PortSpec& spec = d.ports()[port];
    auto ref = bc::resolveVariable(*cell.module, var);
    const bc::TypeDesc& t = cell.module->types[ref->type];
    if (!compatible(spec.type, t) && !(ref->bit >= 0 && spec.type == ElemType::Bool)) {
      diags_.error(celldiag::C033, loc, "'" + var + "' is " + t.name + " but " + dirText(spec.dir) + " '" + spec.name + "' of " +
                                    d.name() + " is " + std::string(elemTypeInfo(spec.type).name));
      return 0;
    }
    if (spec.dir == plant::PortDir::Out && ref->readOnly) {
      diags_.error(celldiag::C033, loc, "'" + var + "' is read-only (CONSTANT) and cannot receive " + d.name() + "." + spec.name);
      return 0;
    }
    cell.wires.push_back(makeWire(d.tag(port), spec.dir, *ref, t.elem, var));
    return 1;
  }

  SourceManager& sources_;
  Diagnostics& diags_;
  st::CompileOptions plcOptions_;
  const bc::Module* precompiled_ = nullptr;
  bool plcBroken_ = false;                  // the `plc:` section or its program has errors
  const ConfigNode* plcModbus_ = nullptr;  // `plc: modbus:` inside the file's tree, read after the devices
  const ConfigNode* plcAds_ = nullptr;     // `plc: ads:` likewise
  const ConfigNode* plcOpcua_ = nullptr;   // `plc: opcua:` likewise
  std::pair<uint32_t, uint32_t> plcFiles_{0, 0};
  struct ExternalRunVariable {
    std::string name;
    SourceLocation loc;
    bool cycleDone = false;  // else recorded
  };
  std::vector<ExternalRunVariable> externalRun_;  // `run:` variables of the PLC behind `plc: ads:`
};

}  // namespace

std::unique_ptr<plant::Device> createDeviceOfEntry(ConfigReader& cfg, const std::string& name, const std::string& type,
                                                   plant::World& world) {
  cfg.child("wiring");  // read by the loader once the device exists
  cfg.child("faults");
  cfg.optString("model", "");  // informational: the real device's make and type
  cfg.optString("description", "");
  // the factory reads the device's own parameters and rejects unknown keys
  return plant::createDevice(type, name, cfg, world, drives::deviceTypes());
}

plant::FaultPlan readFaultPlan(ConfigReader& f, uint32_t defaultAtCommand) {
  plant::FaultPlan p;
  p.errorCode = static_cast<int32_t>(f.optInt("error_code", 0));
  p.errorAtCommand = static_cast<uint32_t>(f.optInt("at_command", p.errorCode ? defaultAtCommand : 0));
  p.extraDelayNs = static_cast<int64_t>(f.optQuantity("extra_delay", Dimension::Time, 0) * 1e9 + 0.5);
  p.doneStuck = f.optBool("done_stuck", false);
  p.stuckOutput = static_cast<int>(f.optInt("stuck_output", -1));
  if (p.stuckOutput < -1 || p.stuckOutput > 1) f.error(f.node().loc(), "'stuck_output' must be 0 or 1 (or -1: not stuck)");
  return p;
}

void readDeviceFaults(plant::Device& d, ConfigReader& f) {
  d.faults() = readFaultPlan(f, 1);
  d.readFaults(f);
  f.rejectUnknownKeys();
}

namespace {

// The PLC program's compile errors first: they are the cause the user must read first.
void sortPlcErrorsFirst(Diagnostics& diags, const Loader& loader) {
  diags.sortByLocation();
  diags.moveFilesFirst(loader.plcFiles().first, loader.plcFiles().second);
}

}  // namespace

std::unique_ptr<Cell> loadCell(const std::string& path, SourceManager& sources, Diagnostics& diags,
                               st::CompileOptions plcOptions) {
  Loader loader(sources, diags, plcOptions);
  auto cell = loader.load(path);
  sortPlcErrorsFirst(diags, loader);
  return cell;
}

std::unique_ptr<Cell> loadCellTree(const std::filesystem::path& file, const ConfigNode& root, SourceManager& sources,
                                   Diagnostics& diags, st::CompileOptions plcOptions) {
  Loader loader(sources, diags, plcOptions);
  auto cell = loader.build(file, root);
  sortPlcErrorsFirst(diags, loader);
  return cell;
}

std::unique_ptr<CellTemplate> loadCellTemplate(const std::string& path, SourceManager& sources, Diagnostics& diags) {
  auto tmpl = std::make_unique<CellTemplate>();
  tmpl->file = path;
  Loader loader(sources, diags);
  std::unique_ptr<Cell> cell;
  if (loader.readTree(path, tmpl->root)) cell = loader.build(tmpl->file, tmpl->root);
  sortPlcErrorsFirst(diags, loader);
  if (!cell) return nullptr;
  tmpl->module = std::move(cell->module);
  return tmpl;
}

std::unique_ptr<Cell> instantiateCell(const CellTemplate& tmpl, const ConfigNode& root, SourceManager& sources, Diagnostics& diags) {
  Loader loader(sources, diags, {}, tmpl.module.get());
  auto cell = loader.build(tmpl.file, root);
  diags.sortByLocation();
  return cell;
}

}  // namespace virtcom::cell
