#include "core/tag_bus.hpp"

#include <cmath>

namespace virtcom {

TagId TagBus::add(std::string name, ElemType type) {
  values_.push_back(0);
  types_.push_back(type);
  names_.push_back(std::move(name));
  if (changed_.size() * 64 < values_.size()) changed_.push_back(0);
  return static_cast<TagId>(values_.size() - 1);
}

double TagBus::getNumber(TagId id) const {
  ElemType t = types_[id];
  if (isFloat(t)) return getReal(id);
  if (isZeroExtendedKind(elemTypeInfo(t).kind))
    return static_cast<double>(values_[id]);
  return static_cast<double>(getInt(id));
}

void TagBus::setNumber(TagId id, double v) {
  ElemType t = types_[id];
  if (isFloat(t)) {
    setReal(id, t == ElemType::Real ? static_cast<double>(static_cast<float>(v)) : v);
  } else if (t == ElemType::Bool) {
    setBool(id, v != 0);
  } else {
    setInt(id, static_cast<int64_t>(std::llround(v)));
  }
}

TagId TagBus::find(const std::string& name) const {
  for (size_t i = 0; i < names_.size(); ++i)
    if (names_[i] == name) return static_cast<TagId>(i);
  return kNoTag;
}

}  // namespace virtcom
