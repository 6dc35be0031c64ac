#include "plc/audited_variables.hpp"

#include <algorithm>

#include "bytecode/variables.hpp"

namespace virtcom::plc {

namespace {

uint32_t sizeOf(const bc::Module& m, const bc::VarRef& r) {
  if (r.bit >= 0) return 1;
  return r.type < m.types.size() ? m.types[r.type].size : 0;
}

// Narrows `ref` (named `name`) to the struct member or array element that holds all of
// [lo, hi), as deep as one does: "MAIN.s" -> "MAIN.s.a[2]".
void narrowRef(const bc::Module& m, std::string& name, bc::VarRef& ref, uint32_t lo, uint32_t hi) {
  while (ref.bit < 0 && ref.type < m.types.size()) {
    const bc::TypeDesc& t = m.types[ref.type];
    if (t.kind == bc::TypeKind::Struct) {
      auto f = std::find_if(t.fields.begin(), t.fields.end(), [&](const bc::Field& f) {
        if (f.absolute || f.bit >= 0 || f.type >= m.types.size()) return false;
        const uint32_t at = ref.address + f.offset;
        return lo >= at && hi <= at + m.types[f.type].size;
      });
      if (f == t.fields.end()) return;
      name += "." + f->name;
      ref = {f->type, ref.address + f->offset, -1, ref.readOnly};
    } else if (t.kind == bc::TypeKind::Array && t.dims.size() == 1 && t.element < m.types.size()) {
      const uint32_t each = m.types[t.element].size;
      if (each == 0) return;
      const uint32_t index = (lo - ref.address) / each;
      const uint32_t at = ref.address + index * each;
      if (index >= t.dims[0].count() || hi > at + each) return;
      name += "[" + std::to_string(t.dims[0].lo + static_cast<int64_t>(index)) + "]";
      ref = {t.element, at, -1, ref.readOnly};
    } else {
      return;
    }
  }
}

// "%QX0.3", "%MW4", "%IB2"...: the IEC address of a variable in a process area, else "".
std::string locationOf(const bc::Module& m, const bc::VarRef& r, uint32_t size) {
  struct Area {
    const bc::ProcessArea& area;
    char letter;
  };
  for (const Area& a : {Area{m.inputs, 'I'}, Area{m.outputs, 'Q'}, Area{m.memory, 'M'}}) {
    if (r.address < a.area.address || r.address - a.area.address >= a.area.size) continue;
    const uint32_t byte = r.address - a.area.address;
    if (r.bit >= 0) return "%" + std::string(1, a.letter) + "X" + std::to_string(byte) + "." + std::to_string(r.bit);
    const char width = size == 1 ? 'B' : size == 2 ? 'W' : size == 4 ? 'D' : 'L';
    return "%" + std::string(1, a.letter) + width + std::to_string(size == 1 ? byte : byte / size);
  }
  return "";
}

bc::VarRef refOf(const AuditedNames::Place& p) { return {static_cast<bc::TypeId>(p.what), p.address, p.bit, false}; }

class AuditedVariables final : public AuditedNames {
 public:
  explicit AuditedVariables(const bc::Module& m) : m_(m), shadow_(m.staticSize) {
    for (bc::NamedVar& v : bc::listVariables(m)) {
      const uint32_t size = sizeOf(m, v.ref);
      if (size > 0) places_.push_back({std::move(v.name), v.ref.address, v.ref.bit, size, v.ref.type});
    }
    std::stable_sort(places_.begin(), places_.end(), [](const Place& a, const Place& b) { return a.address < b.address; });
  }

  const std::vector<Place>& places() const override { return places_; }

  void narrow(Place& p, uint32_t lo, uint32_t hi) const override {
    bc::VarRef ref = refOf(p);
    narrowRef(m_, p.name, ref, lo, hi);
    p = {std::move(p.name), ref.address, ref.bit, sizeOf(m_, ref), ref.type};
  }

  std::optional<std::string> valueText(const Place& p, std::span<const uint8_t> bytes) override {
    if (p.what >= m_.types.size() || p.address + p.size > shadow_.size()) return std::nullopt;
    std::copy(bytes.begin(), bytes.end(), shadow_.begin() + p.address);
    return bc::formatValue(m_, refOf(p), shadow_.data());
  }

  std::string location(const Place& p) const override { return locationOf(m_, refOf(p), p.size); }

 private:
  const bc::Module& m_;
  std::vector<Place> places_;
  std::vector<uint8_t> shadow_;  // the data area's size: where old and new bytes are formatted from
};

}  // namespace

std::unique_ptr<AuditedNames> auditedVariables(const bc::Module& module) { return std::make_unique<AuditedVariables>(module); }

}  // namespace virtcom::plc
