// UDP discovery (docs/ads.md, UDP discovery). Request and reply share one layout, little endian:
//   cookie u32 0x71146603, invoke id u32, service u32 (reply: | 0x80000000),
//   AMS address (NetId 6 bytes, port u16), tag count u32, then tags {id u16, length u16, data}.
#include "proto/ads/discovery.hpp"

#include <algorithm>
#include <string_view>

#include "proto/ads/byte_io.hpp"
#include "proto/ads/device.hpp"

namespace virtcom::proto::ads {

namespace {

constexpr uint32_t kCookie = 0x71146603;
constexpr uint32_t kServiceIdentify = 1, kServiceAddRoute = 6, kServiceReply = 0x80000000;
// Tags: the add-route request's NetId (7) and password (2); the replies' status (1) and computer
// name (5).
constexpr uint16_t kTagStatus = 1, kTagPassword = 2, kTagComputerName = 5, kTagNetId = 7;

void writeHead(LittleEndianWriter& w, uint32_t invokeId, uint32_t service, const AmsNetId& netId, uint32_t tags) {
  w.u32(kCookie);
  w.u32(invokeId);
  w.u32(service | kServiceReply);
  w.bytes(netId);
  w.u16(kSystemPort);
  w.u32(tags);
}

struct RouteRequest {
  AmsNetId netId;                      // its NetId tag, else the sender's
  std::optional<std::string_view> password;  // its password tag, without the NUL
};

RouteRequest readRouteRequest(LittleEndianReader in, const AmsNetId& sender) {
  RouteRequest r{sender, std::nullopt};
  const auto count = in.u32();
  for (uint32_t i = 0; count && i < *count; ++i) {
    const auto tag = in.u16(), length = in.u16();
    if (!tag || !length) break;
    const auto data = in.bytes(*length);
    if (!data) break;
    if (*tag == kTagNetId && data->size() == 6) std::copy(data->begin(), data->end(), r.netId.begin());
    if (*tag == kTagPassword) {
      std::string_view text(reinterpret_cast<const char*>(data->data()), data->size());
      r.password = text.substr(0, text.find('\0'));
    }
  }
  return r;
}

// Compares every byte whatever the first difference, so the time taken does not tell a guesser
// how much of the password was right (only its length).
bool samePassword(std::string_view given, std::string_view expected) {
  if (expected.empty() || given.size() != expected.size()) return false;
  uint8_t diff = 0;
  for (size_t i = 0; i < given.size(); ++i) diff |= static_cast<uint8_t>(given[i] ^ expected[i]);
  return diff == 0;
}

}  // namespace

DiscoveryAnswer answerDiscovery(std::span<const uint8_t> request, const DiscoveryInfo& info, std::vector<uint8_t>& out) {
  LittleEndianReader in(request);
  const auto cookie = in.u32(), invokeId = in.u32(), service = in.u32();
  const auto sender = in.bytes(6);
  if (!cookie || *cookie != kCookie || !service || !sender || !in.u16()) return {};
  AmsNetId senderId;
  std::copy(sender->begin(), sender->end(), senderId.begin());
  LittleEndianWriter w(out);
  switch (*service) {
    case kServiceIdentify:
      writeHead(w, *invokeId, *service, info.netId, 1);
      w.u16(kTagComputerName);
      w.u16(static_cast<uint16_t>(std::min<size_t>(info.hostName.size(), 254) + 1));
      w.cstring(std::string_view(info.hostName).substr(0, 254));
      return {true, false, std::nullopt};
    case kServiceAddRoute: {
      const RouteRequest route = readRouteRequest(in, senderId);
      const bool accepted = route.password && samePassword(*route.password, info.routePassword);
      writeHead(w, *invokeId, *service, info.netId, 1);
      w.u16(kTagStatus);
      w.u16(4);
      w.u32(static_cast<uint32_t>(accepted ? AdsError::None : AdsError::AccessDenied));
      return {true, true, accepted ? std::optional<AmsNetId>(route.netId) : std::nullopt};
    }
    default: return {};
  }
}

}  // namespace virtcom::proto::ads
