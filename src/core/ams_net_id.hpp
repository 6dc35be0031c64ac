#pragma once
// The AmsNetId (ADS address of a device: six numbers, "192.168.1.10.1.1") as text, below the
// layers that name one: the cell file's `plc: ads:` and the ADS server's `--ads-netid` read it
// with the same parser and message. The ADS protocol itself lives in proto/ads.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/text_result.hpp"

namespace virtcom {

using AmsNetId = std::array<uint8_t, 6>;
inline constexpr AmsNetId kLocalAliasNetId{127, 0, 0, 1, 1, 1};
// "a.b.c.d.e.f" with six numbers 0..255. Error text on failure: "'TEXT' is not an AmsNetId
// (six numbers 0-255, e.g. 192.168.1.10.1.1)"; callers prefix the key or option at fault.
TextResult<AmsNetId> parseNetId(std::string_view text);
std::string formatNetId(const AmsNetId& id);

}  // namespace virtcom
