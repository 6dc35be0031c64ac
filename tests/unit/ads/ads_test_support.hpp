#pragma once
// A small hand-made symbol table and AMS frame helpers shared by the ADS unit tests.
//   data area 64 bytes: %I = 16..19, %Q = 20..23, %M = 24..31,
//   MAIN.count INT @32, MAIN.serial DINT @36 (read-only), MAIN.p ST_P @40 {x INT @0, y INT @2}
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "proto/ads/ams.hpp"
#include "proto/ads/byte_io.hpp"
#include "proto/ads/symbol_table.hpp"

namespace virtcom::proto::ads::testing {

using Bytes = std::vector<uint8_t>;

inline SymbolTable makeTable() {
  std::vector<Symbol> symbols = {
      {"MAIN.count", "INT", 0x4040, 32, 2, adst::kInt16, 0},
      {"MAIN.serial", "DINT", 0x4040, 36, 4, adst::kInt32, kSymbolFlagReadOnly},
      {"MAIN.p", "ST_P", 0x4040, 40, 4, adst::kBigType, 0},
  };
  std::vector<DataType> types = {
      {"INT", "", 2, adst::kInt16, kTypeFlagDataType, {}, {}, {}},
      {"DINT", "", 4, adst::kInt32, kTypeFlagDataType, {}, {}, {}},
      {"ST_P", "", 4, adst::kBigType, kTypeFlagDataType, {}, {{"x", "INT", 2, 0, adst::kInt16}, {"y", "INT", 2, 2, adst::kInt16}}, {}},
  };
  MemoryLayout layout{64, {16, 4}, {20, 4}, {24, 8}, {{36, 4}}};
  auto resolver = [symbols](std::string_view path) -> std::optional<Symbol> {
    std::string p = lowerCase(path);
    for (const Symbol& s : symbols)
      if (lowerCase(s.name) == p) return s;
    if (p == "main.p.x") return Symbol{"MAIN.p.x", "INT", 0x4040, 40, 2, adst::kInt16, 0};
    if (p == "main.p.y") return Symbol{"MAIN.p.y", "INT", 0x4040, 42, 2, adst::kInt16, 0};
    return std::nullopt;
  };
  return SymbolTable(symbols, types, layout, resolver);
}

inline constexpr AmsNetId kClientNetId{10, 1, 2, 3, 1, 1};

// An AMS packet from the client (port `sourcePort`) to `port` on `target`.
inline Bytes amsRequest(uint16_t port, uint16_t command, const Bytes& data, uint32_t invokeId = 1,
                        AmsNetId target = kLocalAliasNetId, uint16_t sourcePort = 30000) {
  AmsHeader h;
  h.target = {target, port};
  h.source = {kClientNetId, sourcePort};
  h.commandId = command;
  h.stateFlags = 0x0004;
  h.dataLength = static_cast<uint32_t>(data.size());
  h.invokeId = invokeId;
  Bytes out;
  writeAmsFrameHeader(out, h);
  out.insert(out.end(), data.begin(), data.end());
  return out;
}

// Little-endian u32 fields followed by raw bytes.
inline Bytes u32s(std::initializer_list<uint32_t> values, const Bytes& tail = {}) {
  Bytes out;
  LittleEndianWriter w(out);
  for (uint32_t v : values) w.u32(v);
  w.bytes(tail);
  return out;
}

inline Bytes text(const std::string& s, bool nul = true) {
  Bytes b(s.begin(), s.end());
  if (nul) b.push_back(0);
  return b;
}

inline std::string hex(const Bytes& b) {
  std::string s;
  char buf[4];
  for (size_t i = 0; i < b.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%02x", b[i]);
    if (i) s += ' ';
    s += buf;
  }
  return s;
}

}  // namespace virtcom::proto::ads::testing
