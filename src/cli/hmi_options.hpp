#pragma once
// The web HMI options that `serve` (--http) and `run` (--hmi) share (docs/hmi.md): one
// definition of the flags, their checks (a non-loopback address needs an allow-list and gets a
// token) and of how the HMI hooks into a simulation.
#include <atomic>
#include <expected>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/peer_options.hpp"
#include "hmi/api.hpp"
#include "hmi/http_server.hpp"
#include "cli/sfc_mirror.hpp"
#include "hmi/live_state.hpp"
#include "sim/simulation.hpp"

namespace virtcom::cli {

struct HmiServeOptions {
  std::string listen;     // HOST:PORT; empty: no HMI
  std::string allow;      // --http-allow: IPv4 peers or networks
  std::string token;      // --hmi-token
  bool readOnly = false;  // --hmi-readonly
  bool paused = false;    // --hmi-paused
  bool enabled() const { return !listen.empty(); }
};

// Adds `listenFlag` (--http or --hmi), --http-allow, --hmi-token, --hmi-readonly and
// --hmi-paused to `cmd` (the command adds --allow-any-peer: addPeerFlags).
void addHmiOptions(CLI::App* cmd, HmiServeOptions& o, const std::string& listenFlag);
// Adds where and to whom the page is served: `listenFlag` (described by `what`) and --http-allow
// (what `virtcom history --http`, which only reads, takes of the above).
void addHttpOptions(CLI::App* cmd, HmiServeOptions& o, const std::string& listenFlag, const std::string& what);

// Where and to whom the HMI is served, checked before the cell is loaded.
struct HmiBinding {
  Endpoint at;
  proto::net::PeerPolicy peers;
  hmi::WriteAccess access;
  bool tokenGenerated = false;         // printed at start-up
};
// Error text naming the option at fault. Beyond loopback: an allow-list (or --allow-any-peer in
// `peers`) is required (docs/security.md), and writing needs a token (generated when --hmi-token
// is not given).
std::expected<HmiBinding, std::string> checkHmiOptions(const HmiServeOptions& o, const PeerFlags& peers, const std::string& listenFlag);

// The HMI of a command's runs: construct before the simulation (it hooks into the options),
// serve() once the first simulation is constructed, stop() when done. A reset from the page
// ends the run (resetRequested()); the command then builds the fresh cell (reloadForReset), a
// new simulation over it, restart()s the HMI with it and runs again.
class LiveHmi {
 public:
  LiveHmi(cell::Cell& cell, const std::atomic<bool>* interrupt, bool paused, sim::SimOptions& options);
  // Before serve(): reset answers 409 with `why` (what holds the run's state: an attached
  // protocol server, a file written as the run goes).
  void refuseReset(std::string why) { resetRefusal_ = std::move(why); }
  // Starts the server and prints "hmi: serving http://HOST:PORT/ ..." on stderr. The rule panel
  // lists the rules of the activity diagrams among `sources` (the cell's PLC files). Error text
  // if the address cannot be bound.
  std::expected<void, std::string> serve(const HmiBinding& binding, sim::Simulation& simulation, const SourceManager& sources);
  void stop();
  // Before serve(): the page can show the recorded past of the runs from the history database
  // at `path` (the command's --history; empty: none), over a second, read-only connection.
  void keepHistory(std::string path) { historyPath_ = std::move(path); }
  // Before the run: the page's writes and forces are audited by `audit` (LiveState::auditWrites).
  void auditWrites(WriteAudit* audit) { live_.auditWrites(audit); }
  // virtcom monitor with a plan: the KPI panel shows the current shift's parts against the plan.
  void watchShifts(std::function<void(hmi::ShiftProgress&)> fill) { live_.watchShifts(std::move(fill)); }
  // virtcom monitor over ADS: the SFC panel shows the real PLC's steps, read by `mirror`
  // (which must outlive this).
  void mirrorSteps(const SfcMirror& mirror) {
    mirror_ = &mirror;
    live_.mirrorMemory(mirror.image(), mirror.imageSize());
  }

  // The run just ended on a reset from the page.
  bool resetRequested() const { return live_.resetting(); }
  // After a run that ended by itself: true (once) when the page asks for a reset.
  bool takeReset() { return live_.takeReset(); }
  // The page shows the run of `cell` (from reloadForReset) from now on.
  void restart(cell::Cell& cell) {
    cell_ = &cell;
    live_.restart(cell);
  }

 private:
  cell::Cell* cell_;
  std::string resetRefusal_;
  std::string historyPath_;
  const SfcMirror* mirror_ = nullptr;
  hmi::LiveState live_;
  std::unique_ptr<hmi::HistoryApi> history_;  // before api_, which points at it
  std::unique_ptr<hmi::Api> api_;
  std::unique_ptr<hmi::HttpServer> server_;
};

// A reset's fresh cell: `running`'s file loaded again (new devices, world and trace in their
// initial state), which must still be the same cell (the same PLC program and memory layout,
// devices and signals: the HMI's model and variable catalog stay true). It takes over
// `running`'s PLC module object (the HMI, presets and compiled code point at it) and run
// settings (the command's adjustments). `plcOptions`: how the running cell's program was
// compiled (`run --coverage`: with probes, so the program compares equal and its counts go on
// being recorded). Error text if the files changed or no longer load.
std::expected<std::unique_ptr<cell::Cell>, std::string> reloadForReset(cell::Cell& running, SourceManager& sources,
                                                                       st::CompileOptions plcOptions = {});

}  // namespace virtcom::cli
