// UDP discovery (docs/ads.md, UDP discovery). Request and reply share one layout, little endian:
//   cookie u32 0x71146603, invoke id u32, service u32 (reply: | 0x80000000),
//   AMS address (NetId 6 bytes, port u16), tag count u32, then tags {id u16, length u16, data}.
#include "proto/ads/discovery.hpp"

#include <algorithm>

#include "proto/ads/byte_io.hpp"
#include "proto/ads/device.hpp"

namespace virtcom::proto::ads {

namespace {

constexpr uint32_t kCookie = 0x71146603;
constexpr uint32_t kServiceIdentify = 1, kServiceAddRoute = 6, kServiceReply = 0x80000000;
// Tags: the add-route request's NetId (7); the replies' status (1) and computer name (5).
constexpr uint16_t kTagStatus = 1, kTagComputerName = 5, kTagNetId = 7;

void writeHead(LittleEndianWriter& w, uint32_t invokeId, uint32_t service, const AmsNetId& netId, uint32_t tags) {
  w.u32(kCookie);
  w.u32(invokeId);
  w.u32(service | kServiceReply);
  w.bytes(netId);
  w.u16(kSystemPort);
  w.u32(tags);
}

// The NetId an add-route request asks to be let in: its NetId tag, else the sender's address.
AmsNetId routeNetId(LittleEndianReader in, const AmsNetId& sender) {
  const auto count = in.u32();
  for (uint32_t i = 0; count && i < *count; ++i) {
    const auto tag = in.u16(), length = in.u16();
    if (!tag || !length) break;
    const auto data = in.bytes(*length);
    if (!data) break;
    if (*tag == kTagNetId && data->size() == 6) {
      AmsNetId id;
      std::copy(data->begin(), data->end(), id.begin());
      return id;
    }
  }
  return sender;
}

}  // namespace

bool answerDiscovery(std::span<const uint8_t> request, const DiscoveryInfo& info, std::vector<uint8_t>& out) {
  LittleEndianReader in(request);
  const auto cookie = in.u32(), invokeId = in.u32(), service = in.u32();
  const auto sender = in.bytes(6);
  if (!cookie || *cookie != kCookie || !service || !sender || !in.u16()) return false;
  AmsNetId senderId;
  std::copy(sender->begin(), sender->end(), senderId.begin());
  LittleEndianWriter w(out);
  switch (*service) {
    case kServiceIdentify:
      writeHead(w, *invokeId, *service, info.netId, 1);
      w.u16(kTagComputerName);
      w.u16(static_cast<uint16_t>(std::min<size_t>(info.hostName.size(), 254) + 1));
      w.cstring(std::string_view(info.hostName).substr(0, 254));
      return true;
    case kServiceAddRoute: {
      // No credentials to check: any NetId is served unless an allow-list is given, and UDP
      // never widens that list; a NetId outside it is refused (0x704), one inside accepted.
      const AmsNetId id = routeNetId(in, senderId);
      const bool allowed = info.allowedNetIds.empty() ||
                           std::find(info.allowedNetIds.begin(), info.allowedNetIds.end(), id) != info.allowedNetIds.end();
      writeHead(w, *invokeId, *service, info.netId, 1);
      w.u16(kTagStatus);
      w.u16(4);
      w.u32(static_cast<uint32_t>(allowed ? AdsError::None : AdsError::AccessDenied));
      return true;
    }
    default: return false;
  }
}

}  // namespace virtcom::proto::ads
