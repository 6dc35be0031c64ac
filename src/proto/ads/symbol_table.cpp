#include "proto/ads/symbol_table.hpp"

#include "core/ascii.hpp"

namespace virtcom::proto::ads {

std::string lowerCase(std::string_view s) { return asciiLower(s); }

SymbolTable::SymbolTable(std::vector<Symbol> symbols, std::vector<DataType> types, MemoryLayout layout, Resolver resolver)
    : symbols_(std::move(symbols)),
      types_(std::move(types)),
      layout_(std::move(layout)),
      resolver_(std::move(resolver)),
      readOnlyBytes_(layout_.dataSize, false) {
  for (size_t i = 0; i < types_.size(); ++i) typeIndex_.emplace(lowerCase(types_[i].name), i);
  for (const ByteRange& r : layout_.readOnly)
    for (uint64_t b = r.offset; b < uint64_t{r.offset} + r.size && b < readOnlyBytes_.size(); ++b) readOnlyBytes_[b] = true;
}

std::optional<Symbol> SymbolTable::find(std::string_view path) const {
  if (!resolver_) return std::nullopt;
  return resolver_(path);
}

const DataType* SymbolTable::findType(std::string_view name) const {
  auto it = typeIndex_.find(lowerCase(name));
  return it == typeIndex_.end() ? nullptr : &types_[it->second];
}

bool SymbolTable::touchesReadOnly(uint32_t offset, uint32_t size) const {
  for (uint64_t b = offset; b < uint64_t{offset} + size && b < readOnlyBytes_.size(); ++b)
    if (readOnlyBytes_[b]) return true;
  return false;
}

}  // namespace virtcom::proto::ads
