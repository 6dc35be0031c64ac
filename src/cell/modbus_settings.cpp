#include "cell/modbus_settings.hpp"

#include <optional>

#include "cell/peer_settings.hpp"

namespace virtcom::cell {

std::vector<modbus_map::BusSignal> busSignals(const Cell& cell) {
  std::vector<modbus_map::BusSignal> out;
  for (const auto& d : cell.devices)
    for (size_t i = 0; i < d->ports().size(); ++i) {
      const plant::PortSpec& p = d->ports()[i];
      auto dir = p.dir == plant::PortDir::In ? modbus_map::SignalDir::Command : modbus_map::SignalDir::Status;
      out.push_back({d->tag(i), d->name() + "." + p.name, p.type, dir});
    }
  return out;
}

void detachSoftPlc(Cell& cell) {
  cell.module.reset();
  cell.wires.clear();
  cell.run.until = {};
  cell.run.cycleDoneVar.clear();
  cell.run.recordVars.clear();
  cell.run.cycleDoneTag = kNoTag;
}

void readModbusSection(Cell& cell, const ConfigNode* node, Diagnostics& diags) {
  auto signals = busSignals(cell);
  if (!node) {
    cell.modbus = modbus_map::parseSignalMap(nullptr, signals, modbus_map::MapRole::Server);
    return;
  }
  ConfigReader r(*node, diags, "'modbus'");
  if (node->kind() != ConfigNode::Kind::Map) {
    r.error(node->loc(), "'modbus' must be a map with 'map:' (a list of entries) and optional 'word_order:' and 'cycle_done:'");
    return;
  }
  // `cycle_done:` publishes the soft PLC's cycle marker (`run: cycle_done`), which a Modbus
  // client cannot read by name: a tag of its own, which the simulation copies from the PLC.
  std::optional<modbus_map::BusSignal> marker;
  if (const ConfigNode* at = node->find("cycle_done")) {
    if (cell.run.cycleDoneVar.empty()) {
      r.child("cycle_done");  // reported here, not as an unknown key
      r.error(at->loc(), "'cycle_done' publishes the PLC's cycle marker, but the cell names none: add 'run: cycle_done: VARIABLE' "
                         "(a BOOL of the soft PLC)");
    } else {
      TagId tag = cell.bus.find(cell.run.cycleDoneVar);
      if (tag == kNoTag) tag = cell.bus.add(cell.run.cycleDoneVar, ElemType::Bool);
      marker = modbus_map::BusSignal{tag, cell.run.cycleDoneVar, ElemType::Bool, modbus_map::SignalDir::Status};
    }
  }
  cell.modbus = modbus_map::parseSignalMap(&r, signals, modbus_map::MapRole::Server, marker ? &*marker : nullptr);
  r.rejectUnknownKeys();
}

void readModbusClient(Cell& cell, const ConfigNode& node, Diagnostics& diags) {
  ConfigReader r(node, diags, "'plc: modbus'");
  if (node.kind() != ConfigNode::Kind::Map) {
    r.error(node.loc(), "'plc: modbus' must be a map with 'address: HOST:PORT' of the external PLC");
    return;
  }
  ModbusClientSettings s;
  readPeerAddress(r, node, "127.0.0.1:502", s.address, s.peer);
  int64_t unit = r.optInt("unit", 1);
  if (unit < 0 || unit > 255) r.error(node.find("unit")->loc(), "'unit' must be 0..255");
  s.unit = static_cast<int>(unit);
  s.pollNs = readLinkDurationNs(r, node, "poll", 0.01);
  s.timeoutNs = readLinkDurationNs(r, node, "timeout", 0.5);
  s.faultOnLoss = readFaultOnLoss(r, node);
  auto signals = busSignals(cell);
  // `cycle_done:` places the PLC's cycle marker in its tables (a Modbus PLC has no variables by
  // name): the bridge reads it with the commands and the run counts its rising edges, as it does
  // `run: cycle_done` of a soft or ADS PLC.
  std::optional<modbus_map::BusSignal> marker;
  if (node.find("cycle_done"))
    marker = modbus_map::BusSignal{cell.bus.add(kModbusCycleDoneSignal, ElemType::Bool), kModbusCycleDoneSignal, ElemType::Bool,
                                   modbus_map::SignalDir::Command};
  s.map = modbus_map::parseSignalMap(&r, signals, modbus_map::MapRole::Client, marker ? &*marker : nullptr);
  if (s.map.cycleDone != kNoTag) cell.run.cycleDoneTag = s.map.cycleDone;
  r.rejectUnknownKeys();
  cell.plcModbus = std::move(s);
}

}  // namespace virtcom::cell
