#include "proto/ads/handle_table.hpp"

#include <algorithm>

namespace virtcom::proto::ads {

size_t HandleTable::routeIndex(const AmsAddress& owner) const {
  // A linear search: few routes hold handles at once, and it allocates nothing.
  auto it = std::find_if(routes_.begin(), routes_.end(), [&](const Route& r) { return r.owner == owner; });
  return static_cast<size_t>(it - routes_.begin());
}

const Symbol* HandleTable::find(const AmsAddress& owner, uint32_t handle) const {
  const size_t i = routeIndex(owner);
  if (i == routes_.size()) return nullptr;
  const Route& r = routes_[i];
  if (handle == 0 || handle > r.slots.size() || !r.slots[handle - 1].used) return nullptr;
  return &r.slots[handle - 1].symbol;
}

AdsError HandleTable::create(const AmsAddress& owner, const Symbol& symbol, uint32_t& handle) {
  const size_t i = routeIndex(owner);
  if (i == routes_.size()) {
    if (routes_.size() >= maxRoutes_) return AdsError::OutOfMemory;
    routes_.push_back(Route{owner, {}, 0});
  }
  Route* route = &routes_[i];
  auto free = std::find_if(route->slots.begin(), route->slots.end(), [](const Slot& s) { return !s.used; });
  if (free == route->slots.end()) {
    if (route->slots.size() >= maxPerRoute_) return AdsError::OutOfMemory;
    free = route->slots.insert(route->slots.end(), Slot{});
  }
  *free = Slot{true, symbol};
  ++route->used;
  handle = static_cast<uint32_t>(free - route->slots.begin() + 1);
  return AdsError::None;
}

AdsError HandleTable::release(const AmsAddress& owner, uint32_t handle) {
  if (!find(owner, handle)) return AdsError::SymbolNotFound;
  const size_t i = routeIndex(owner);
  routes_[i].slots[handle - 1] = Slot{};
  if (--routes_[i].used == 0) routes_.erase(routes_.begin() + static_cast<ptrdiff_t>(i));
  return AdsError::None;
}

void HandleTable::releaseRoute(const AmsAddress& owner) {
  const size_t i = routeIndex(owner);
  if (i != routes_.size()) routes_.erase(routes_.begin() + static_cast<ptrdiff_t>(i));
}

size_t HandleTable::count(const AmsAddress& owner) const {
  const size_t i = routeIndex(owner);
  return i == routes_.size() ? 0 : routes_[i].used;
}

}  // namespace virtcom::proto::ads
