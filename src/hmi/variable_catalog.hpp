#pragma once
// The soft PLC's variables by name, for the HMI's watch table: every elementary, string and enum
// leaf under the module's symbols (struct members, array elements), listed once at start-up so
// that a search or a watched variable never walks the types again.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "bytecode/module.hpp"

namespace virtcom::hmi {

struct CatalogVariable {
  std::string name;  // "MAIN.Robot1.execute", "MAIN.state[3]"
  bc::VarRef ref;
};

class VariableCatalog {
 public:
  // Arrays list at most kMaxElements elements each and the catalogue at most kMaxVariables
  // names; a variable beyond them is still found by its exact name (find()).
  static constexpr uint64_t kMaxElements = 64;
  static constexpr size_t kMaxVariables = 20000;

  explicit VariableCatalog(const bc::Module* module);  // null: no soft PLC, an empty catalogue

  const bc::Module* module() const { return module_; }
  // Names containing `text` (ASCII case-insensitive), in declaration order, at most `limit`.
  std::vector<const CatalogVariable*> search(std::string_view text, size_t limit) const;
  // The variable of this name (case-insensitive, as resolveVariable reads it), or nullopt.
  std::optional<bc::VarRef> find(std::string_view name) const;
  const std::string& typeName(const bc::VarRef& ref) const { return module_->types[ref.type].name; }

 private:
  void add(std::string name, const bc::VarRef& ref);
  const bc::Module* module_;
  std::vector<CatalogVariable> variables_;
};

}  // namespace virtcom::hmi
