#pragma once
// Symbol handles as TwinCAT keeps them: per AMS route (the client's source NetId and port), not
// per TCP connection, so a handle one process created is valid in the next one that opens the
// same AMS port (Beckhoff's adstool test script relies on it). A handle lives until its route
// releases it (0xF006) or the server stops (docs/ads.md, Symbol handles). Not thread-safe: the
// server holds its device lock around every call.
#include <cstdint>
#include <vector>

#include "proto/ads/ams.hpp"
#include "proto/ads/symbol_table.hpp"

namespace virtcom::proto::ads {

class HandleTable {
 public:
  HandleTable(size_t maxPerRoute, size_t maxRoutes) : maxPerRoute_(maxPerRoute), maxRoutes_(maxRoutes) {}

  // The symbol behind `handle` for `owner`; nullptr if that route holds no such handle.
  // No allocation: a lookup per read or write by handle.
  const Symbol* find(const AmsAddress& owner, uint32_t handle) const;
  // A new handle (never 0) for `owner`; 0x70A once the route or the table is full.
  AdsError create(const AmsAddress& owner, const Symbol& symbol, uint32_t& handle);
  // 0x710 if `owner` holds no such handle. A route whose last handle goes is forgotten.
  AdsError release(const AmsAddress& owner, uint32_t handle);
  // Forgets every handle of `owner` (its AMS port closed).
  void releaseRoute(const AmsAddress& owner);
  size_t count(const AmsAddress& owner) const;
  size_t routeCount() const { return routes_.size(); }

 private:
  struct Slot {
    bool used = false;
    Symbol symbol;
  };
  struct Route {
    AmsAddress owner;
    std::vector<Slot> slots;  // handle h is slots[h - 1]
    size_t used = 0;
  };
  // Index of `owner`'s route in routes_; routes_.size() if it holds no handle.
  size_t routeIndex(const AmsAddress& owner) const;

  size_t maxPerRoute_, maxRoutes_;
  std::vector<Route> routes_;
};

}  // namespace virtcom::proto::ads
