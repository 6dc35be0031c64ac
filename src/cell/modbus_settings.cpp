#include "cell/modbus_settings.hpp"

#include <cmath>

#include "proto/net/endpoint.hpp"

namespace virtcom::cell {

std::vector<proto::modbus::BusSignal> busSignals(const Cell& cell) {
  std::vector<proto::modbus::BusSignal> out;
  for (const auto& d : cell.devices)
    for (size_t i = 0; i < d->ports().size(); ++i) {
      const plant::PortSpec& p = d->ports()[i];
      auto dir = p.dir == plant::PortDir::In ? proto::modbus::SignalDir::Command : proto::modbus::SignalDir::Status;
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
    cell.modbus = proto::modbus::parseSignalMap(nullptr, signals, proto::modbus::MapRole::Server);
    return;
  }
  ConfigReader r(*node, diags, "'modbus'");
  if (node->kind() != ConfigNode::Kind::Map) {
    r.error(node->loc(), "'modbus' must be a map with 'map:' (a list of entries) and optional 'word_order:'");
    return;
  }
  cell.modbus = proto::modbus::parseSignalMap(&r, signals, proto::modbus::MapRole::Server);
  r.rejectUnknownKeys();
}

void readModbusClient(Cell& cell, const ConfigNode& node, Diagnostics& diags) {
  ConfigReader r(node, diags, "'plc: modbus'");
  if (node.kind() != ConfigNode::Kind::Map) {
    r.error(node.loc(), "'plc: modbus' must be a map with 'address: HOST:PORT' of the external PLC");
    return;
  }
  ModbusClientSettings s;
  s.address = r.requireString("address");
  if (!s.address.empty()) {
    auto endpoint = proto::net::parseEndpoint(s.address);
    if (!endpoint || endpoint->port == 0)
      r.error(node.find("address")->loc(), "'address': " + (endpoint ? std::string("port 0 cannot be connected to") : endpoint.error()) +
                                               " (expected HOST:PORT, e.g. 127.0.0.1:502)");
  }
  int64_t unit = r.optInt("unit", 1);
  if (unit < 0 || unit > 255) r.error(node.find("unit")->loc(), "'unit' must be 0..255");
  s.unit = static_cast<int>(unit);
  s.pollNs = static_cast<int64_t>(std::llround(r.optQuantity("poll", Dimension::Time, 0.01) * 1e9));
  if (s.pollNs < 1'000'000) r.error(node.find("poll")->loc(), "'poll' must be at least 1 ms");
  s.timeoutNs = static_cast<int64_t>(std::llround(r.optQuantity("timeout", Dimension::Time, 0.5) * 1e9));
  if (s.timeoutNs < 1'000'000) r.error(node.find("timeout")->loc(), "'timeout' must be at least 1 ms");
  std::string onLoss = r.optString("on_loss", "fault");
  if (onLoss != "fault" && onLoss != "hold") r.error(node.find("on_loss")->loc(), "'on_loss' must be fault or hold, not '" + onLoss + "'");
  s.faultOnLoss = onLoss == "fault";
  auto signals = busSignals(cell);
  s.map = proto::modbus::parseSignalMap(&r, signals, proto::modbus::MapRole::Client);
  r.rejectUnknownKeys();
  cell.plcModbus = std::move(s);
}

}  // namespace virtcom::cell
