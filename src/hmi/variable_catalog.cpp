#include "hmi/variable_catalog.hpp"

#include "core/ascii.hpp"

namespace virtcom::hmi {

VariableCatalog::VariableCatalog(const bc::Module* module) : module_(module) {
  if (!module_) return;
  for (const bc::Symbol& s : module_->symbols) add(s.name, {s.type, s.address, -1, s.readOnly});
}

// Depth first, so the catalogue reads in declaration order.
void VariableCatalog::add(std::string name, const bc::VarRef& ref) {
  if (variables_.size() >= kMaxVariables) return;
  const bc::TypeDesc& t = module_->types[ref.type];
  switch (t.kind) {
    case bc::TypeKind::Elementary:
    case bc::TypeKind::String:
    case bc::TypeKind::Enum: variables_.push_back({std::move(name), ref}); return;
    case bc::TypeKind::Struct:
      for (const bc::Field& f : t.fields) {
        if (f.hidden) continue;
        uint32_t address = f.absolute ? f.offset : ref.address + f.offset;
        add(name + "." + f.name, {f.type, address, f.bit, ref.readOnly || f.readOnly});
      }
      return;
    case bc::TypeKind::Array: {
      uint32_t stride = module_->types[t.element].size;
      uint64_t total = 1;
      for (const bc::ArrayDim& d : t.dims) total *= d.count();
      for (uint64_t flat = 0; flat < total && flat < kMaxElements; ++flat) {
        std::string index;
        uint64_t rest = flat;
        for (size_t k = t.dims.size(); k-- > 0;) {  // last index varies fastest
          uint64_t count = t.dims[k].count();
          index = std::to_string(t.dims[k].lo + static_cast<int64_t>(rest % count)) + (index.empty() ? "" : "," + index);
          rest /= count;
        }
        add(name + "[" + index + "]", {t.element, ref.address + static_cast<uint32_t>(flat) * stride, -1, ref.readOnly});
      }
      return;
    }
    case bc::TypeKind::Pointer:
    case bc::TypeKind::Reference: return;  // their target is not a variable of its own
  }
}

std::vector<const CatalogVariable*> VariableCatalog::search(std::string_view text, size_t limit) const {
  std::string needle = asciiLower(text);
  std::vector<const CatalogVariable*> found;
  for (const CatalogVariable& v : variables_) {
    if (found.size() >= limit) break;
    if (needle.empty() || asciiLower(v.name).find(needle) != std::string::npos) found.push_back(&v);
  }
  return found;
}

std::optional<bc::VarRef> VariableCatalog::find(std::string_view name) const {
  if (!module_) return std::nullopt;
  return bc::resolveVariable(*module_, name);
}

}  // namespace virtcom::hmi
