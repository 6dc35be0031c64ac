// The `virtcom` command.
#include <iostream>

#include "cli/commands.hpp"
#include "cli/common.hpp"

int main(int argc, char** argv) {
  CLI::App app{"virtcom - virtual commissioning engine: runs IEC 61131-3 control logic against a simulated cell"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "virtcom 0.1.0");
  using virtcom::cli::ExitCode;
  ExitCode exitCode = ExitCode::Ok;
  auto setExit = [&](ExitCode code) { exitCode = code; };
  virtcom::cli::addCheckCommand(app, setExit);
  virtcom::cli::addExecCommand(app, setExit);
  virtcom::cli::addRunCommand(app, setExit);
  virtcom::cli::addServeCommand(app, setExit);
  virtcom::cli::addMonitorCommand(app, setExit);
  virtcom::cli::addModbusMapCommand(app, setExit);
  virtcom::cli::addExportCommand(app, setExit);
  virtcom::cli::addAdCommand(app, setExit);
  virtcom::cli::addHistoryCommand(app, setExit);
  virtcom::cli::addTestCommand(app, setExit);
  virtcom::cli::addOptimiseCommand(app, setExit);
  virtcom::cli::addSweepCommand(app, setExit);
  virtcom::cli::addOpcuaUserCommand(app, setExit);
  if (argc > 1) {
    std::string first = argv[1];
    bool known = first == "-h" || first == "--help" || first == "--version";
    for (const auto* sub : app.get_subcommands({})) known = known || first == sub->get_name();
    if (!known) {
      std::cerr << "virtcom: unknown " << (first.rfind('-', 0) == 0 ? "option '" : "command '") << first
                << "' (commands: check, exec, run, serve, modbus-map, export, ad, history; see virtcom --help)\n";
      return static_cast<int>(ExitCode::Usage);
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11 prints --help and --version through this path too, with status 0.
    return static_cast<int>(app.exit(e) == 0 ? ExitCode::Ok : ExitCode::Usage);
  }
  return static_cast<int>(exitCode);
}
