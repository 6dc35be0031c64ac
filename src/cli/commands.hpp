#pragma once
#include <functional>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/exit_code.hpp"

namespace virtcom::cli {
// `--backend interp|aot` (see compiledBackend in common.hpp), stored into `backend`.
void addBackendOption(CLI::App& cmd, std::string& backend);

// Each subcommand registers itself and reports its exit status through `setExit`.
void addCheckCommand(CLI::App& app, std::function<void(ExitCode)> setExit);
void addExecCommand(CLI::App& app, std::function<void(ExitCode)> setExit);
void addRunCommand(CLI::App& app, std::function<void(ExitCode)> setExit);
void addServeCommand(CLI::App& app, std::function<void(ExitCode)> setExit);
void addMonitorCommand(CLI::App& app, std::function<void(ExitCode)> setExit);
void addModbusMapCommand(CLI::App& app, std::function<void(ExitCode)> setExit);
void addExportCommand(CLI::App& app, std::function<void(ExitCode)> setExit);
void addAdCommand(CLI::App& app, std::function<void(ExitCode)> setExit);
}  // namespace virtcom::cli
