#pragma once
// The ADS server: AMS/TCP on one endpoint, answering as a TwinCAT 3 PLC runtime (AMS port 851)
// and its system service (port 10000). Built so the network never races the scan:
//  - one I/O thread owns the sockets (poll, non-blocking) and answers every request from the
//    snapshot of the memory image published after the last scan (consistent, never torn);
//  - writes are checked, queued and applied by the scan thread before the next scan
//    (applyPendingWrites), each request whole, in arrival order; RUN/STOP requests likewise;
//  - notifications are evaluated on the I/O thread after each publish and on their cycle.
// One mutex guards the device state; it is held while answering one frame or copying the image,
// never across socket I/O. Neither scan-side call allocates.
#include <atomic>
#include <cstdint>
#include <expected>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "proto/ads/device.hpp"
#include "proto/ads/discovery.hpp"
#include "proto/ads/symbol_table.hpp"
#include "proto/net/endpoint.hpp"
#include "proto/net/peer_policy.hpp"
#include "proto/net/server_thread.hpp"

namespace virtcom::proto::ads {

inline constexpr uint16_t kAmsTcpPort = 48898;

struct ServerConfig {
  net::Endpoint listen{0x7f000001, kAmsTcpPort};
  // Who may connect (IPv4 peers; also the UDP discovery's), how many at once, how fast
  // (docs/security.md); a connection beyond it is accepted and closed at once, a request beyond
  // the rate answered with ADS error 0x708 (device busy).
  net::PeerPolicy peers;
  std::vector<AmsNetId> allowedNetIds;  // source NetIds; empty: any (no route check, as on localhost)
  DeviceConfig device;
  size_t maxFrameBytes = 1024 * 1024;   // a longer AMS/TCP frame closes its connection
  // UDP discovery (identify, add route: discovery.hpp) on listen's address at this port
  // (TwinCAT: kDiscoveryUdpPort; the CLI's default); 0: any free port, nullopt: off. A port that
  // cannot be bound leaves the TCP server running without it (discoveryProblem()).
  std::optional<uint16_t> discoveryPort;
  // The password a UDP add route must carry (--ads-route-password); empty: every add route is
  // refused (0x704). An accepted one adds its NetId to allowedNetIds and the sender's address to
  // the peers' allow-list, when those lists are in use (docs/ads.md, Routes).
  std::string routePassword;
  // Called on the I/O thread for each route a UDP add route adds (the CLI persists it in the
  // --ads-routes file, as TwinCAT does in StaticRoutes.xml); may be empty.
  std::function<void(const AmsNetId& netId, uint32_t ipv4)> onRouteAdded;
};

// The scan thread's memory: the data area the symbol table describes, and the external input
// image the next scan copies into the %I area (writes to %I go to both).
struct LiveImage {
  std::span<uint8_t> data;
  std::span<uint8_t> inputImage;
};

class Server {
 public:
  // Binds, listens and starts the I/O thread. `table` must outlive the server. Error text if
  // the address cannot be bound or the thread cannot start. The snapshot is all zero until
  // publishSnapshot().
  static std::expected<std::unique_ptr<Server>, std::string> start(const ServerConfig& config, const SymbolTable& table);
  ~Server();  // stop()
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  net::Endpoint endpoint() const { return io_.bound(); }
  // The UDP discovery endpoint, if it is served; else why not ("" when it is off).
  std::optional<net::Endpoint> discoveryEndpoint() const { return discovery_; }
  const std::string& discoveryProblem() const { return discoveryProblem_; }

  // Scan thread, before a scan: applies every queued write to `live`; returns how many edits.
  size_t applyPendingWrites(const LiveImage& live, WriteObserver* audit = nullptr);
  // Scan thread, before a scan: a RUN (5) or STOP (6) a client asked for with WriteControl.
  std::optional<StateRequest> takeStateRequest();
  // Scan thread, after a scan: copies the data area into the snapshot and wakes the I/O thread
  // when notifications are registered.
  void publishSnapshot(std::span<const uint8_t> data, uint16_t adsState);

  // Connections currently open (for tests and diagnostics).
  size_t connectionCount() const { return connections_.load(); }

  // Closes every connection and joins the I/O thread. Idempotent.
  void stop();

 private:
  Server(const ServerConfig& config, const SymbolTable& table);
  void run();
  void openDiscovery();
  // I/O thread, once the UDP socket is readable: answers every datagram waiting.
  void answerDatagrams();
  // I/O thread: an accepted add route lets `netId` at `ipv4` in (the lists in use grow).
  void addRoute(const AmsNetId& netId, uint32_t ipv4);

  ServerConfig config_;
  std::mutex mutex_;  // guards device_ and every session
  Device device_;
  std::atomic<size_t> notifications_{0};
  std::atomic<size_t> connections_{0};
  int udpFd_ = -1;
  std::optional<net::Endpoint> discovery_;
  std::string discoveryProblem_;
  DiscoveryInfo discoveryInfo_;
  std::vector<uint8_t> datagram_, reply_;  // sized once: answering allocates nothing
  net::ServerThread io_;  // runs run(); last, so its thread ends before the members it uses
};

}  // namespace virtcom::proto::ads
