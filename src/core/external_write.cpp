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

std::string writerAddress(const ExternalWriter& w) { return formatIpv4(w.ipv4) + ":" + std::to_string(w.port); }

}  // namespace virtcom
