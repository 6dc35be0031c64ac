#include "core/external_write.hpp"

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

}  // namespace virtcom
