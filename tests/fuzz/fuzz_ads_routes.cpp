// libFuzzer target for the ADS routes file (`--ads-routes FILE`, docs/ads.md, Routes):
// parseAdsRoutes (the cell loader's YAML reader, then the routes: name, netid, address) on any
// bytes. A refused file always has a diagnostic; every route accepted has an AmsNetId whose text
// reads back as the same NetId.
#include <cstddef>
#include <cstdint>
#include <string>

#include "cell/ads_routes.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  virtcom::SourceManager sources;
  virtcom::Diagnostics diags;
  const auto routes = virtcom::cell::parseAdsRoutes("routes.yaml", text, sources, diags);
  if (!routes) {
    if (!diags.hasErrors()) __builtin_trap();  // a refused file always says why
    return 0;
  }
  for (const virtcom::cell::AdsRoute& r : *routes) {
    const auto netId = virtcom::parseNetId(virtcom::formatNetId(r.netId));
    if (!netId || *netId != r.netId) __builtin_trap();
  }
  return 0;
}
