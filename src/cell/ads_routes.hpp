#pragma once
// The ADS route table of `--ads-routes FILE` (docs/ads.md, Routes): the peers the soft PLC's ADS
// server lets in, as TwinCAT's StaticRoutes.xml holds them, in the cell files' YAML:
//   routes:
//     - name: hmi-pc
//       netid: 192.168.1.20.1.1
//       address: 192.168.1.20
// Read with positions (file:line:col diagnostics); a route added over UDP with the password is
// appended to the file, as TwinCAT persists it.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/ams_net_id.hpp"
#include "core/diagnostics.hpp"
#include "core/source.hpp"

namespace virtcom::cell {

struct AdsRoute {
  std::string name;
  AmsNetId netId{};
  uint32_t ipv4 = 0;
};

// The routes in `text`, the content of `path` (empty: none, as for a file that does not exist
// yet). Every problem is a diagnostic at its position (YAML syntax, a key missing, unknown or
// malformed); nullopt then.
std::optional<std::vector<AdsRoute>> parseAdsRoutes(const std::string& path, const std::string& text, SourceManager& sources,
                                                    Diagnostics& diags);

// Appends `route` to `path` (created with its `routes:` key when absent). Error text on failure.
std::string appendAdsRoute(const std::string& path, const AdsRoute& route);

}  // namespace virtcom::cell
