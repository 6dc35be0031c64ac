#include "proto/modbus/client_bridge.hpp"

#include <modbus.h>

#include <algorithm>
#include <array>
#include <cerrno>

namespace virtcom::proto::modbus {

namespace {

// Largest reads a request may ask for: MODBUS Application Protocol V1.1b3, sections 6.1-6.4.
constexpr uint16_t kMaxReadBits = 2000;
constexpr uint16_t kMaxReadRegisters = 125;

bool isException(int error) { return error > MODBUS_ENOBASE && error < MODBUS_ENOBASE + 0x20; }

// Commands of one table sorted by address, merged into runs of consecutive addresses.
std::vector<ClientBridge::ReadBlock> readBlocks(std::vector<MapEntry> entries);

}  // namespace

ClientBridge::ClientBridge(ClientConfig config)
    : config_(std::move(config)),
      mirror_(tablesFor(config_.map)),
      written_(tablesFor(config_.map)),
      link_({"modbus", "the PLC at " + net::formatEndpoint(config_.peer), "every poll", config_.faultOnLoss, config_.report}) {
  for (const MapEntry& e : config_.map.entries) (e.dir == SignalDir::Command ? commands_ : status_).push_back(e);
  blocks_ = readBlocks(commands_);
  dirty_.assign(status_.size(), true);
  ctx_ = modbus_new_tcp(net::formatIpv4(config_.peer.ipv4).c_str(), config_.peer.port);
  if (ctx_) {
    modbus_set_slave(ctx_, config_.unit);
    auto us = config_.timeoutNs / 1000;
    modbus_set_response_timeout(ctx_, static_cast<uint32_t>(us / 1'000'000), static_cast<uint32_t>(us % 1'000'000));
  }
}

ClientBridge::~ClientBridge() {
  if (!ctx_) return;
  if (connected_) modbus_close(ctx_);
  modbus_free(ctx_);
}

bool ClientBridge::connect() {
  if (connected_) return true;
  if (!ctx_ || modbus_connect(ctx_) != 0) {
    lose(std::string("cannot connect: ") + (ctx_ ? modbus_strerror(errno) : "out of memory"));
    return false;
  }
  connected_ = true;
  link_.reconnected();
  std::fill(dirty_.begin(), dirty_.end(), true);  // the PLC may have lost what was written
  return true;
}

void ClientBridge::lose(const std::string& what) {
  if (connected_) modbus_close(ctx_);
  connected_ = false;
  link_.lost(what);
}

bool ClientBridge::readBlock(const ReadBlock& b) {
  std::array<uint16_t, kMaxReadRegisters> regs;
  std::array<uint8_t, kMaxReadBits> bits;
  ++requests_;
  int n = -1;
  switch (b.table) {
    case Table::Coil: n = modbus_read_bits(ctx_, b.address, b.count, bits.data()); break;
    case Table::DiscreteInput: n = modbus_read_input_bits(ctx_, b.address, b.count, bits.data()); break;
    case Table::HoldingRegister: n = modbus_read_registers(ctx_, b.address, b.count, regs.data()); break;
    case Table::InputRegister: n = modbus_read_input_registers(ctx_, b.address, b.count, regs.data()); break;
  }
  if (n != b.count) {
    int error = errno;
    std::string what = std::string("reading ") + tableName(b.table) + " " + std::to_string(b.address) + ".." +
                       std::to_string(b.address + b.count - 1) + ": " + modbus_strerror(error);
    if (isException(error)) link_.refused("refused " + what);
    else lose(what);
    return false;
  }
  std::span<uint8_t> bytes = tableBytes(mirror_.view(), b.table);
  for (uint16_t i = 0; i < b.count; ++i) {
    if (isBitTable(b.table)) setBit(bytes, b.address + i, bits[i] != 0);
    else setRegister(bytes, b.address + i, regs[i]);
  }
  return true;
}

bool ClientBridge::writeEntry(const MapEntry& e) {
  std::span<const uint8_t> now = tableBytes(mirror_.view(), e.table);
  std::array<uint16_t, 2> regs{};
  ++requests_;
  int n = -1;
  if (isBitTable(e.table)) {
    n = modbus_write_bit(ctx_, e.address, getBit(now, e.address) ? 1 : 0);
  } else {
    for (uint32_t i = 0; i < e.width(); ++i) regs[i] = getRegister(now, e.address + i);
    n = e.width() == 1 ? modbus_write_register(ctx_, e.address, regs[0]) : modbus_write_registers(ctx_, e.address, 2, regs.data());
  }
  if (n < 0) {
    int error = errno;
    std::string what = std::string("writing ") + e.signal + " to " + tableName(e.table) + " " + std::to_string(e.address) + ": " + modbus_strerror(error);
    if (isException(error)) link_.refused("refused " + what);
    else lose(what);
    return false;
  }
  std::span<uint8_t> done = tableBytes(written_.view(), e.table);
  if (isBitTable(e.table)) setBit(done, e.address, getBit(now, e.address));
  else
    for (uint32_t i = 0; i < e.width(); ++i) setRegister(done, e.address + i, regs[i]);
  return true;
}

bool ClientBridge::pull(TagBus& bus, int64_t nowNs) {
  pollNow_ = nowNs >= nextPollNs_;
  if (pollNow_) {
    nextPollNs_ = nowNs + config_.pollNs;
    bool ok = connect();
    for (size_t i = 0; ok && i < blocks_.size(); ++i) ok = readBlock(blocks_[i]);
    if (ok)
      for (const MapEntry& e : commands_) loadSignal(e, mirror_.view(), bus);
  }
  return !link_.failed();
}

void ClientBridge::push(const TagBus& bus, int64_t) {
  if (!pollNow_ || !connected_) return;
  for (size_t i = 0; i < status_.size() && connected_ && !link_.failed(); ++i) {
    const MapEntry& e = status_[i];
    storeSignal(e, bus, mirror_.view());
    std::span<const uint8_t> now = tableBytes(mirror_.view(), e.table), done = tableBytes(written_.view(), e.table);
    bool changed = isBitTable(e.table) ? getBit(now, e.address) != getBit(done, e.address)
                                       : !std::equal(now.begin() + 2 * e.address, now.begin() + 2 * (e.address + e.width()),
                                                     done.begin() + 2 * e.address);
    if ((changed || dirty_[i]) && writeEntry(e)) dirty_[i] = false;
  }
}

namespace {

std::vector<ClientBridge::ReadBlock> readBlocks(std::vector<MapEntry> entries) {
  std::sort(entries.begin(), entries.end(), [](const MapEntry& a, const MapEntry& b) {
    return a.table != b.table ? a.table < b.table : a.address < b.address;
  });
  std::vector<ClientBridge::ReadBlock> blocks;
  for (const MapEntry& e : entries) {
    uint32_t end = e.address + e.width();
    uint32_t limit = isBitTable(e.table) ? kMaxReadBits : kMaxReadRegisters;
    if (!blocks.empty()) {
      auto& last = blocks.back();
      uint32_t lastEnd = last.address + last.count;
      if (last.table == e.table && e.address <= lastEnd && end - last.address <= limit) {
        last.count = static_cast<uint16_t>(std::max(lastEnd, end) - last.address);
        continue;
      }
    }
    blocks.push_back({e.table, e.address, static_cast<uint16_t>(e.width())});
  }
  return blocks;
}

}  // namespace

}  // namespace virtcom::proto::modbus
