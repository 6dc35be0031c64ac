#pragma once
// A Modbus TCP server for a PLC process image, built so the network never races the scan:
//  - one I/O thread owns the sockets (poll, non-blocking) and answers requests from a snapshot
//    of the image; writes update the snapshot and are queued as byte edits;
//  - the scan thread calls applyPendingWrites() before each scan (every queued request lands
//    whole, in arrival order) and publishSnapshot() after it (reads see a scan boundary).
// The one mutex is held only while answering one frame (<= 260 bytes) or copying the image;
// never across socket I/O, and neither scan-side call allocates.
#include <cstdint>
#include <expected>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "proto/modbus/pdu.hpp"
#include "proto/net/endpoint.hpp"
#include "proto/net/peer_policy.hpp"
#include "proto/net/server_thread.hpp"

namespace virtcom::proto::modbus {

// Endpoints and allow-lists are shared with the ADS server (proto/net).
using net::Endpoint;
using net::formatEndpoint;
using net::parseEndpoint;

struct ServerConfig {
  Endpoint listen{0x7f000001, 1502};
  // Who may connect, how many at once, how fast (docs/security.md); a connection beyond it is
  // accepted and closed at once, a request beyond the rate answered with exception 06.
  net::PeerPolicy peers;
  bool readOnly = false;  // every write refused with exception 01 (ImageView::readOnly)
  // Queued byte edits between two scans; beyond: exception 06. 65536 edits (512 KiB) take a
  // client writing 10 registers per request at more than 300 000 requests/s for a 10 ms scan.
  size_t pendingEditCapacity = 65536;
};

// The areas the server exposes (the live image's spans must have these sizes) and their layout.
struct ImageShape {
  size_t inputs = 0, outputs = 0, memory = 0, registers = 0;
  Layout layout = Layout::OpenPlc;
  std::vector<uint8_t> readOnlyCoils, readOnlyHolding;  // see ImageView
  bool writableInputs = false;                          // see ImageView
};

class Server {
 public:
  // Binds, listens and starts the I/O thread. Error text if the address cannot be bound or the
  // thread cannot start. The initial snapshot is all zero until publishSnapshot().
  static std::expected<std::unique_ptr<Server>, std::string> start(const ServerConfig& config, ImageShape shape);
  ~Server();  // stop()
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  // The bound endpoint (the real port when 0 was asked for).
  Endpoint endpoint() const { return io_.bound(); }

  // Scan thread, between scans: applies every queued write to `live` and empties the queue,
  // each edit reported to `audit` (if given). Returns the number of byte edits applied. No
  // allocation (but the audit's, when there were writes); locks only to copy.
  size_t applyPendingWrites(const ImageView& live, WriteObserver* audit = nullptr);
  // Scan thread, after a scan: copies `live` into the snapshot requests are answered from, then
  // re-applies writes still queued so a client reads back what it wrote. No allocation.
  void publishSnapshot(const ImageView& live);

  // Closes every connection and joins the I/O thread. Idempotent.
  void stop();

 private:
  Server(const ServerConfig& config, ImageShape shape);
  void run();

  ServerConfig config_;
  ImageShape shape_;
  std::mutex mutex_;  // guards snapshot_* and pending_
  std::vector<uint8_t> snapshotInputs_, snapshotOutputs_, snapshotMemory_, snapshotRegisters_;
  ImageView snapshot_;
  EditQueue pending_;
  net::ServerThread io_;  // runs run(); last, so its thread ends before the members it uses
};

}  // namespace virtcom::proto::modbus
