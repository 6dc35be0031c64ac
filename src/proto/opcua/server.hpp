#pragma once
// The OPC UA server: opc.tcp on one endpoint. Built as the ADS server is, so the network never
// races the scan:
//  - one I/O thread owns the sockets (poll, non-blocking) and answers every request from the
//    snapshot of the memory image published after the last scan (consistent, never torn);
//  - writes are checked, queued and applied by the scan thread before the next scan
//    (applyPendingWrites), each request whole, in arrival order;
//  - subscriptions are sampled and published on the I/O thread, on their own timers.
// One mutex guards the server state; it is held while answering one message or copying the
// image, never across socket I/O. Neither scan-side call allocates.
#include <atomic>
#include <cstdint>
#include <expected>
#include <memory>
#include <mutex>
#include <span>
#include <string>

#include "proto/ads/symbol_table.hpp"
#include "proto/net/server_thread.hpp"
#include "proto/opcua/server_core.hpp"

namespace virtcom::proto::opcua {

// The scan thread's memory: the data area and the external input image (as ads::LiveImage).
struct LiveImage {
  std::span<uint8_t> data;
  std::span<uint8_t> inputImage;
};

class Server {
 public:
  // Binds, listens and starts the I/O thread. `table` must outlive the server. Error text if the
  // address cannot be bound or the thread cannot start.
  static std::expected<std::unique_ptr<Server>, std::string> start(const ServerConfig& config, const ads::SymbolTable& table);
  ~Server();  // stop()
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  net::Endpoint endpoint() const { return io_.bound(); }
  std::string endpointUrl();
  const ServerConfig& config() const { return config_; }

  // Scan thread, before a scan: applies every queued write to `live`; returns how many edits.
  size_t applyPendingWrites(const LiveImage& live, WriteObserver* audit = nullptr);
  // Scan thread, after a scan: copies the data area (and the values of the extra objects, the
  // cell's devices) into the snapshot.
  void publishSnapshot(std::span<const uint8_t> data, std::span<const uint8_t> extra = {});

  size_t connectionCount() const { return connections_.load(); }
  void stop() { io_.stop(); }

 private:
  Server(const ServerConfig& config, const ads::SymbolTable& table);
  void run();

  ServerConfig config_;
  const ads::SymbolTable& table_;
  std::mutex mutex_;  // guards core_ and every channel
  ServerCore core_;
  std::atomic<size_t> connections_{0};
  net::ServerThread io_;  // runs run(); last, so its thread ends before the members it uses
};

}  // namespace virtcom::proto::opcua
