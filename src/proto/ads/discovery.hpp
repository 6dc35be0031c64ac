#pragma once
// The TwinCAT UDP service on port 48899 that engineering tools use before they open AMS/TCP:
// "identify" (AdsLib's GetRemoteAddress behind `adstool HOST netid`, pyads
// adsGetNetIdForPLC) and "add route" (AdsLib's AddRemoteRoute, pyads add_route_to_plc).
// Pure codec (no sockets): the server feeds it datagrams (docs/ads.md, UDP discovery).
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "proto/ads/ams.hpp"

namespace virtcom::proto::ads {

inline constexpr uint16_t kDiscoveryUdpPort = 48899;

struct DiscoveryInfo {
  AmsNetId netId{};
  std::string hostName;       // the "computer name" tag of the identify reply
  std::string routePassword;  // what an add route must carry (--ads-route-password); empty: every add route refused
};

struct DiscoveryAnswer {
  bool replied = false;                 // a reply was appended
  bool addRoute = false;                // the request was an add route
  std::optional<AmsNetId> routeAdded;   // an add route with the right password: the NetId to let in
  explicit operator bool() const { return replied; }
};

// Appends the reply to one datagram to `out`. Not replied (nothing appended) when there is
// nothing to answer: not the UDP cookie, too short, a reply, or a service other than identify /
// add route. An add route is accepted only with the configured password; otherwise, as TwinCAT
// with wrong credentials, its status is 0x704. Allocates only if `out` has to grow.
DiscoveryAnswer answerDiscovery(std::span<const uint8_t> request, const DiscoveryInfo& info, std::vector<uint8_t>& out);

}  // namespace virtcom::proto::ads
