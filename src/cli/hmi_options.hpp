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

#include "hmi/api.hpp"
#include "hmi/http_server.hpp"
#include "hmi/live_state.hpp"
#include "sim/simulation.hpp"

namespace virtcom::cli {

struct HmiServeOptions {
  std::string listen;     // HOST:PORT; empty: no HMI
  std::string allow;      // --http-allow: IPv4 peers
  bool anyPeer = false;   // --allow-any-peer
  std::string token;      // --hmi-token
  bool readOnly = false;  // --hmi-readonly
  bool paused = false;    // --hmi-paused
  bool enabled() const { return !listen.empty(); }
};

// Adds `listenFlag` (--http or --hmi), --http-allow, --allow-any-peer, --hmi-token,
// --hmi-readonly and --hmi-paused to `cmd`.
void addHmiOptions(CLI::App* cmd, HmiServeOptions& o, const std::string& listenFlag);

// Where and to whom the HMI is served, checked before the cell is loaded.
struct HmiBinding {
  Endpoint at;
  std::vector<uint32_t> allowedPeers;  // empty: any
  hmi::WriteAccess access;
  bool tokenGenerated = false;         // printed at start-up
};
// Error text naming the option at fault. Beyond loopback: an allow-list (or --allow-any-peer) is
// required, and writing needs a token (generated when --hmi-token is not given).
std::expected<HmiBinding, std::string> checkHmiOptions(const HmiServeOptions& o, const std::string& listenFlag);

// The HMI of one run: construct before the simulation (it hooks into the options), serve() once
// the simulation is constructed, stop() when done.
class LiveHmi {
 public:
  LiveHmi(cell::Cell& cell, const std::atomic<bool>* interrupt, bool paused, sim::SimOptions& options);
  // Starts the server and prints "hmi: serving http://HOST:PORT/ ..." on stderr. Error text if
  // the address cannot be bound.
  std::expected<void, std::string> serve(const HmiBinding& binding, sim::Simulation& simulation);
  void stop();
  // virtcom monitor with a plan: the KPI panel shows the current shift's parts against the plan.
  void watchShifts(std::function<void(hmi::ShiftProgress&)> fill) { live_.watchShifts(std::move(fill)); }

 private:
  cell::Cell& cell_;
  hmi::LiveState live_;
  std::unique_ptr<hmi::Api> api_;
  std::unique_ptr<hmi::HttpServer> server_;
};

}  // namespace virtcom::cli
