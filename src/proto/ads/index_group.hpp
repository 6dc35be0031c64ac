#pragma once
// The index groups the server answers, from index_groups.def.
#include <cstdint>

namespace virtcom::proto::ads {

enum class IndexGroup : uint32_t {
#define ADS_INDEX_GROUP(name, value) name = value,
#include "proto/ads/index_groups.def"
#undef ADS_INDEX_GROUP
};

inline bool isKnownGroup(uint32_t ig) {
  switch (static_cast<IndexGroup>(ig)) {
#define ADS_INDEX_GROUP(name, value) case IndexGroup::name:
#include "proto/ads/index_groups.def"
#undef ADS_INDEX_GROUP
      return true;
  }
  return false;
}

// "Any length": the client does not know the size and takes what the server has (docs/ads.md, Commands).
inline constexpr uint32_t kAnyLength = 0xFFFFFFFF;

}  // namespace virtcom::proto::ads
