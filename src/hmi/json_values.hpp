#pragma once
// How the page receives values and activities (docs/hmi.md), the same in the live stream's
// frames (stream_session.cpp) and in the history answers (history_api.cpp).
#include <bit>
#include <cstdint>

#include <nlohmann/json.hpp>

#include "core/trace.hpp"

namespace virtcom::hmi {

// A tag's raw bus value as a JSON number or boolean.
inline nlohmann::json signalValue(ElemType type, uint64_t raw) {
  if (type == ElemType::Bool) return raw != 0;
  if (isFloat(type)) return std::bit_cast<double>(raw);
  if (isInteger(type) && !isSignedInt(type)) return raw;
  return static_cast<int64_t>(raw);
}

// [index, device, label, start ns, end ns (-1: running), error code, energy J]
inline nlohmann::json activityJson(uint32_t index, const ActivityRecord& a) {
  return nlohmann::json::array({index, a.device, a.label, a.startNs, a.endNs, a.errorCode, a.energyJ});
}

}  // namespace virtcom::hmi
