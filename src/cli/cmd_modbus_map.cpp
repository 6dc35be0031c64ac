// `virtcom modbus-map`: print a cell's Modbus map (served signals, or the client bridge's map of
// the external PLC) as CSV or Markdown for the PLC programmer.
#include <fstream>
#include <iostream>

#include "cli/commands.hpp"
#include "cli/common.hpp"
#include "core/modbus_map.hpp"

namespace virtcom::cli {

namespace {

struct MapOptions {
  std::string cellFile;
  std::string format = "csv";
  std::string output;
  bool bridge = false;
};

ExitCode printMap(const MapOptions& o) {
  SourceManager sources;
  auto cell = loadCellFile(o.cellFile, sources);
  if (!cell) return ExitCode::InputError;
  if (o.bridge && !cell->plcModbus) {
    std::cerr << "error: " << o.cellFile << ": --bridge: the cell has no 'plc: modbus:' section (an external PLC it polls)\n";
    return ExitCode::Usage;
  }
  const auto& map = o.bridge ? cell->plcModbus->map : cell->modbus;
  std::string text = o.format == "csv" ? modbus_map::formatMapCsv(map) : modbus_map::formatMapMarkdown(map);
  if (o.output.empty()) {
    std::cout << text;
    return ExitCode::Ok;
  }
  std::ofstream out(o.output, std::ios::binary);
  if (!(out << text)) {
    std::cerr << "error: cannot write " << o.output << "\n";
    return ExitCode::Usage;
  }
  return ExitCode::Ok;
}

}  // namespace

void addModbusMapCommand(CLI::App& app, std::function<void(ExitCode)> setExit) {
  auto o = std::make_shared<MapOptions>();
  CLI::App* cmd = app.add_subcommand("modbus-map", "Print the Modbus map of a cell (address, table, type, signal, direction, scaling)");
  cmd->add_option("cell", o->cellFile, "the cell file (YAML)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--format", o->format, "csv (default) or markdown")->check(CLI::IsMember({"csv", "markdown"}));
  cmd->add_option("-o,--output", o->output, "write the table to this file instead of stdout");
  cmd->add_flag("--bridge", o->bridge, "print the map of 'plc: modbus:' (the external PLC's tables) instead of the served one");
  cmd->callback([o, setExit] { setExit(printMap(*o)); });
}

}  // namespace virtcom::cli
