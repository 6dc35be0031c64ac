#include "proto/ads/plc/plc_binding.hpp"

#include "proto/ads/plc/module_symbols.hpp"

namespace virtcom::proto::ads {

uint16_t adsStateOf(plc::PlcState s) {
  switch (s) {
    case plc::PlcState::Run: return kAdsStateRun;
    case plc::PlcState::Stop: return kAdsStateStop;
    case plc::PlcState::Fault: return kAdsStateError;
  }
  return kAdsStateError;
}

void beforeScan(Server& server, plc::Runtime& runtime, WriteObserver* audit) {
  if (auto request = server.takeStateRequest()) {
    const char* from = plc::stateName(runtime.state());
    if (request->adsState == kAdsStateRun) runtime.start();
    else runtime.stop();
    if (audit) audit->stateChanged(request->writer, from, plc::stateName(runtime.state()));
  }
  const bc::Module& m = runtime.module();
  LiveImage live{{runtime.machine().memory(), m.staticSize}, {runtime.inputImage(), m.inputs.size}};
  if (server.applyPendingWrites(live, audit) > 0) runtime.inputsTouched();
}

void afterScan(Server& server, plc::Runtime& runtime) {
  server.publishSnapshot({runtime.machine().memory(), runtime.module().staticSize}, adsStateOf(runtime.state()));
}

}  // namespace virtcom::proto::ads

namespace virtcom::proto::ads {

std::expected<std::unique_ptr<PlcServer>, std::string> PlcServer::start(const ServerConfig& config, const bc::Module& module) {
  std::unique_ptr<PlcServer> s(new PlcServer(buildSymbolTable(module)));
  auto server = Server::start(config, s->table_);
  if (!server) return std::unexpected(server.error());
  s->server_ = std::move(*server);
  return s;
}

}  // namespace virtcom::proto::ads
