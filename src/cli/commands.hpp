#pragma once
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/exit_code.hpp"

namespace virtcom::cli {
// `--backend auto|interp|aot` (cli/plc_backend.hpp), stored into `backend`.
void addBackendOption(CLI::App& cmd, std::string& backend);
// `--trace-window N`: how many activities and cycles a run keeps (sim::SimOptions::traceWindow).
void addTraceWindowOption(CLI::App& cmd, size_t& window);

// Each subcommand registers itself and reports its exit status through `setExit`.
void addCheckCommand(CLI::App& app, std::function<void(ExitCode)> setExit);
void addExecCommand(CLI::App& app, std::function<void(ExitCode)> setExit);
void addRunCommand(CLI::App& app, std::function<void(ExitCode)> setExit);
void addServeCommand(CLI::App& app, std::function<void(ExitCode)> setExit);
void addMonitorCommand(CLI::App& app, std::function<void(ExitCode)> setExit);
void addModbusMapCommand(CLI::App& app, std::function<void(ExitCode)> setExit);
void addExportCommand(CLI::App& app, std::function<void(ExitCode)> setExit);
void addAdCommand(CLI::App& app, std::function<void(ExitCode)> setExit);
void addHistoryCommand(CLI::App& app, std::function<void(ExitCode)> setExit);
void addTestCommand(CLI::App& app, std::function<void(ExitCode)> setExit);
void addOptimiseCommand(CLI::App& app, std::function<void(ExitCode)> setExit);
void addSweepCommand(CLI::App& app, std::function<void(ExitCode)> setExit);
void addOpcuaUserCommand(CLI::App& app, std::function<void(ExitCode)> setExit);
// `ad convert` and `ad export` (cmd_ad_files.cpp), registered under `ad` by addAdCommand.
void addAdFileCommands(CLI::App& ad, std::function<void(ExitCode)> setExit);

// Compiles the files (printing diagnostics) and writes them as one PLCopen TC6 project to `out`;
// `name` is the project name (empty: the stem of `out`). `virtcom export` and `ad export`.
ExitCode exportPlcopen(const std::string& out, const std::string& name, const std::vector<std::string>& files);
// `virtcom ad render`, a subcommand of `ad` (cmd_ad_render.cpp).
void addAdRenderCommand(CLI::App& ad, std::function<void(ExitCode)> setExit);
}  // namespace virtcom::cli
