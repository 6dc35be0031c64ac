#pragma once
// Serving a soft PLC over ADS: the two calls a scan loop makes around each scan, and PlcServer,
// which bundles the program's symbol table with the server over it.
#include <expected>
#include <memory>
#include <string>

#include "plc/runtime.hpp"
#include "proto/ads/server.hpp"
#include "proto/ads/symbol_table.hpp"

namespace virtcom::proto::ads {

// Before a scan: applies a client's RUN/STOP and every queued write (located inputs also go to
// the external input image, so the scan's input copy keeps them). No allocation.
// Each write is reported to `audit` (if given; core/write_audit.hpp).
void beforeScan(Server& server, plc::Runtime& runtime, WriteObserver* audit = nullptr);
// After a scan: publishes the memory image and the PLC state to the server. No allocation.
void afterScan(Server& server, plc::Runtime& runtime);

uint16_t adsStateOf(plc::PlcState s);

// A compiled program served over ADS (`virtcom exec --ads`, `virtcom serve --ads`): the scan
// loop calls afterScan() once after the cold start (before announcing the server, so clients
// never see an empty image), then beforeScan()/afterScan() around every scan.
class PlcServer {
 public:
  // Builds the symbol table of `module` (which must outlive the server) and starts the server.
  static std::expected<std::unique_ptr<PlcServer>, std::string> start(const ServerConfig& config, const bc::Module& module);

  void beforeScan(plc::Runtime& runtime, WriteObserver* audit = nullptr) { ads::beforeScan(*server_, runtime, audit); }
  void afterScan(plc::Runtime& runtime) { ads::afterScan(*server_, runtime); }
  Server& server() { return *server_; }
  void stop() { server_->stop(); }

 private:
  explicit PlcServer(SymbolTable table) : table_(std::move(table)) {}
  SymbolTable table_;
  std::unique_ptr<Server> server_;
};

}  // namespace virtcom::proto::ads
