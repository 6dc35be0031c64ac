#include "core/external_write.hpp"

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

}  // namespace virtcom
