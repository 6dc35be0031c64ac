#pragma once
// The tag bus: every signal exchanged between the PLC, the devices, the protocol bridges and the
// recorders lives here in a typed 64-bit slot addressed by an integer id resolved at load time.
// Writes that change a value set its bit in the change set, so recorders and bridges only look
// at what changed. Nothing on the per-tick path allocates or looks anything up by name.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "core/iec_value.hpp"

namespace virtcom {

using TagId = uint32_t;
inline constexpr TagId kNoTag = 0xffffffffu;

class TagBus {
 public:
  // Registers a signal; names are unique (the caller checks). Allocates: load time only.
  TagId add(std::string name, ElemType type);
  size_t size() const { return values_.size(); }
  const std::string& name(TagId id) const { return names_[id]; }
  ElemType type(TagId id) const { return types_[id]; }

  // Typed access. Integers are stored sign/zero extended, BOOL as 0/1, REAL/LREAL as double.
  bool getBool(TagId id) const { return values_[id] != 0; }
  int64_t getInt(TagId id) const { return static_cast<int64_t>(values_[id]); }
  double getReal(TagId id) const { return std::bit_cast<double>(values_[id]); }
  // Numeric value whatever the type (for scaling/recording).
  double getNumber(TagId id) const;
  uint64_t raw(TagId id) const { return values_[id]; }

  void setBool(TagId id, bool v) { setRaw(id, v ? 1 : 0); }
  void setInt(TagId id, int64_t v) { setRaw(id, static_cast<uint64_t>(v)); }
  void setReal(TagId id, double v) { setRaw(id, std::bit_cast<uint64_t>(v)); }
  // Stores `v` converted to the tag's type (rounding reals for integer tags).
  void setNumber(TagId id, double v);
  void setRaw(TagId id, uint64_t v) {
    if (values_[id] == v) return;
    values_[id] = v;
    changed_[id >> 6] |= uint64_t(1) << (id & 63);
  }

  bool changed(TagId id) const { return (changed_[id >> 6] >> (id & 63)) & 1; }
  // Calls fn(id) for every tag changed since the last clearChanges(), in id order.
  template <typename F>
  void forEachChanged(F&& fn) const {
    for (size_t w = 0; w < changed_.size(); ++w) {
      uint64_t bits = changed_[w];
      while (bits) {
        int b = std::countr_zero(bits);
        fn(static_cast<TagId>(w * 64 + static_cast<size_t>(b)));
        bits &= bits - 1;
      }
    }
  }
  // (std::fill, not memset: an empty bus has a null data() that memset must not get)
  void clearChanges() { std::fill(changed_.begin(), changed_.end(), uint64_t{0}); }
  // Finds a tag by exact name; kNoTag if none. Load time only.
  TagId find(const std::string& name) const;

 private:
  std::vector<uint64_t> values_;
  std::vector<ElemType> types_;
  std::vector<std::string> names_;
  std::vector<uint64_t> changed_;
};

}  // namespace virtcom
