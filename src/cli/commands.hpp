#pragma once
#include <functional>
#include <string>

#include <CLI/CLI.hpp>

namespace virtcom::cli {
// `--backend interp|aot` (see compiledBackend in common.hpp), stored into `backend`.
void addBackendOption(CLI::App& cmd, std::string& backend);

// Each subcommand registers itself and reports its exit code through `setExit`.
void addCheckCommand(CLI::App& app, std::function<void(int)> setExit);
void addExecCommand(CLI::App& app, std::function<void(int)> setExit);
void addRunCommand(CLI::App& app, std::function<void(int)> setExit);
void addServeCommand(CLI::App& app, std::function<void(int)> setExit);
void addModbusMapCommand(CLI::App& app, std::function<void(int)> setExit);
void addExportCommand(CLI::App& app, std::function<void(int)> setExit);
void addAdCommand(CLI::App& app, std::function<void(int)> setExit);
}  // namespace virtcom::cli
