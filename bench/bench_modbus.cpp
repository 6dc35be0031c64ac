// virtcom_modbus_bench: Modbus TCP requests per second and median round trip on loopback, the
// same libmodbus client against
//   (a) virtcom's server serving examples/modbus-cell with the cell simulated behind it (paced
//       to the wall clock, 10 ms ticks: the server publishes a snapshot every tick), and
//   (b) a minimal reference server: libmodbus's modbus_receive/modbus_reply on a plain
//       modbus_mapping_t, one client, on its own thread.
// Both in the same run; docs/performance.md ("Modbus TCP") has the figures and the ratio.
//   virtcom_modbus_bench [REQUESTS]     (default 20000 per case)
#include <arpa/inet.h>
#include <modbus.h>
#include <netinet/in.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "cell/cell.hpp"
#include "core/clock.hpp"
#include "proto/modbus/signal_server.hpp"
#include "sim/simulation.hpp"

namespace {

using namespace virtcom;

constexpr int kRegisters = 10;

struct Result {
  double requestsPerSecond = 0;
  double medianUs = 0;
};

// `requests` round trips of `request` on a connected client, one at a time.
Result measure(modbus_t* ctx, int requests, const std::function<bool(modbus_t*)>& request) {
  std::vector<int64_t> rtt(static_cast<size_t>(requests));
  for (int i = 0; i < requests / 10; ++i) request(ctx);  // warm up
  int64_t start = monotonicNowNs();
  for (auto& t : rtt) {
    int64_t before = monotonicNowNs();
    if (!request(ctx)) {
      std::fprintf(stderr, "request failed: %s\n", modbus_strerror(errno));
      std::exit(1);
    }
    t = monotonicNowNs() - before;
  }
  int64_t total = monotonicNowNs() - start;
  std::nth_element(rtt.begin(), rtt.begin() + requests / 2, rtt.end());
  return {requests / (static_cast<double>(total) * 1e-9), static_cast<double>(rtt[static_cast<size_t>(requests / 2)]) * 1e-3};
}

bool readHolding(modbus_t* ctx) {
  uint16_t regs[kRegisters];
  return modbus_read_registers(ctx, 0, kRegisters, regs) == kRegisters;
}

bool writeHolding(modbus_t* ctx) {
  // Programme numbers 0 and the unmapped registers up to 9: no device starts.
  static const uint16_t values[kRegisters] = {};
  return modbus_write_registers(ctx, 0, kRegisters, values) == kRegisters;
}

modbus_t* connect(int port) {
  modbus_t* ctx = modbus_new_tcp("127.0.0.1", port);
  if (!ctx || modbus_connect(ctx) != 0) {
    std::fprintf(stderr, "cannot connect to port %d: %s\n", port, modbus_strerror(errno));
    std::exit(1);
  }
  return ctx;
}

// (b) The reference: one client served by modbus_receive/modbus_reply until it disconnects.
class ReferenceServer {
 public:
  ReferenceServer() {
    ctx_ = modbus_new_tcp("127.0.0.1", 0);
    mapping_ = modbus_mapping_new(16, 16, 16, 16);
    listenFd_ = modbus_tcp_listen(ctx_, 1);
    sockaddr_in addr{};
    socklen_t len = sizeof addr;
    getsockname(listenFd_, reinterpret_cast<sockaddr*>(&addr), &len);
    port_ = ntohs(addr.sin_port);
    thread_ = std::thread([this] {
      modbus_tcp_accept(ctx_, &listenFd_);
      uint8_t query[MODBUS_TCP_MAX_ADU_LENGTH];
      while (true) {
        int n = modbus_receive(ctx_, query);
        if (n > 0) modbus_reply(ctx_, query, n, mapping_);
        else if (n < 0) break;
      }
    });
  }
  ~ReferenceServer() {
    thread_.join();
    modbus_mapping_free(mapping_);
    modbus_close(ctx_);
    modbus_free(ctx_);
  }
  int port() const { return port_; }

 private:
  modbus_t* ctx_ = nullptr;
  modbus_mapping_t* mapping_ = nullptr;
  int listenFd_ = -1;
  int port_ = 0;
  std::thread thread_;
};

void print(const char* server, const char* request, const Result& r) {
  std::printf("%-34s %-22s %12.0f %12.1f\n", server, request, r.requestsPerSecond, r.medianUs);
}

}  // namespace

int main(int argc, char** argv) {
  int requests = argc > 1 ? std::atoi(argv[1]) : 20000;
  SourceManager sources;
  Diagnostics diags;
  auto cell = cell::loadCell(VIRTCOM_MODBUS_CELL, sources, diags);
  if (!cell) {
    std::fputs(diags.render(sources).c_str(), stderr);
    return 1;
  }
  proto::modbus::ServerConfig config;
  config.listen = {0x7f000001, 0};
  auto served = proto::modbus::SignalServer::start(config, cell->modbus);
  if (!served) {
    std::fprintf(stderr, "%s\n", served.error().c_str());
    return 1;
  }
  std::atomic<bool> stop{false};
  sim::SimOptions options;
  options.speed = 1;
  options.interrupt = &stop;
  options.timeLimitNs = INT64_MAX;
  options.bridges.push_back(served->get());
  std::thread simulation([&] { sim::Simulation(*cell, options).run(); });

  std::printf("%-34s %-22s %12s %12s\n", "server", "request", "requests/s", "median us");
  modbus_t* client = connect((*served)->endpoint().port);
  Result virtcomRead = measure(client, requests, readHolding);
  Result virtcomWrite = measure(client, requests, writeHolding);
  modbus_close(client);
  modbus_free(client);
  stop = true;
  simulation.join();

  Result refRead, refWrite;
  {
    ReferenceServer reference;
    modbus_t* c = connect(reference.port());
    refRead = measure(c, requests, readHolding);
    refWrite = measure(c, requests, writeHolding);
    modbus_close(c);
    modbus_free(c);
  }
  print("virtcom serve (cell running)", "FC3 read 10 registers", virtcomRead);
  print("reference (modbus_reply)", "FC3 read 10 registers", refRead);
  print("virtcom serve (cell running)", "FC16 write 10 registers", virtcomWrite);
  print("reference (modbus_reply)", "FC16 write 10 registers", refWrite);
  std::printf("median round trip virtcom/reference: FC3 %.2fx, FC16 %.2fx (target <= 1.2x)\n", virtcomRead.medianUs / refRead.medianUs,
              virtcomWrite.medianUs / refWrite.medianUs);
  return 0;
}
