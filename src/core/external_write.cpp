#include "core/external_write.hpp"

#include <cstdio>
#include <ctime>

#include "core/endpoint.hpp"

namespace virtcom {

std::string_view writeProtocolName(WriteProtocol p) {
  switch (p) {
    case WriteProtocol::Ads: return "ads";
    case WriteProtocol::Modbus: return "modbus";
    case WriteProtocol::OpcUa: return "opcua";
    case WriteProtocol::Http: return "http";
  }
  return "?";
}

std::string externalWritesText(std::span<const uint64_t, kWriteProtocolCount> counts) {
  uint64_t total = 0;
  std::string each;
  for (size_t p = 0; p < kWriteProtocolCount; ++p) {
    total += counts[p];
    each += (p ? ", " : "") + std::string(writeProtocolName(static_cast<WriteProtocol>(p))) + " " + std::to_string(counts[p]);
  }
  return std::to_string(total) + " external writes (" + each + ")";
}

std::string writerAddress(const ExternalWriter& w) { return formatIpv4(w.ipv4) + ":" + std::to_string(w.port); }

std::string writerPeer(const ExternalWriter& w) {
  std::string out = writerAddress(w);
  if (w.hasNetId) out += " (AmsNetId " + formatNetId(w.netId) + ")";
  return out;
}

std::string writtenVariableText(const WriteRecord& r) {
  if (r.location.empty() || r.location == r.variable) return r.variable;
  return r.variable + " (" + r.location + ")";
}

std::string utcTimeText(int64_t ns) {
  const std::time_t seconds = static_cast<std::time_t>(ns / 1'000'000'000);
  std::tm tm{};
  gmtime_r(&seconds, &tm);
  char text[64];  // room for any year the int fields can hold (-Wformat-truncation)
  std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday, tm.tm_hour,
                tm.tm_min, tm.tm_sec, static_cast<int>(ns / 1'000'000 % 1000));
  return text;
}

}  // namespace virtcom
