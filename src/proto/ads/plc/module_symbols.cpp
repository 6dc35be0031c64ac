#include "proto/ads/plc/module_symbols.hpp"

#include <algorithm>
#include <unordered_set>

#include "bytecode/variables.hpp"
#include "core/ascii.hpp"
#include "proto/ads/index_group.hpp"

namespace virtcom::proto::ads {

namespace {


uint32_t adsTypeOf(const bc::Module& m, bc::TypeId id) {
  const bc::TypeDesc& t = m.types[id];
  switch (t.kind) {
    case bc::TypeKind::Elementary:
    case bc::TypeKind::String:
    case bc::TypeKind::Enum: return ads::adsTypeOf(t.elem);
    case bc::TypeKind::Array: return t.element < m.types.size() ? adsTypeOf(m, t.element) : adst::kBigType;
    case bc::TypeKind::Struct: return adst::kBigType;
    case bc::TypeKind::Pointer:
    case bc::TypeKind::Reference: return t.size == 8 ? adst::kUint64 : adst::kUint32;
  }
  return adst::kVoid;
}

// Fields an ADS client sees as members: declared, not internal, inside the instance.
bool isMember(const bc::Field& f) { return !f.hidden && !f.absolute && f.bit < 0; }

class Builder {
 public:
  explicit Builder(const bc::Module& m) : m_(m) {}

  void variable(const std::string& name, bc::TypeId type, uint32_t address, int bit, bool readOnly) {
    auto s = symbolFor(m_, name, bc::VarRef{type, address, static_cast<int8_t>(bit), readOnly});
    if (!s) return;
    symbols_.push_back(*s);
    if (bit < 0) {
      collectType(type);
      collectReadOnly(type, address, readOnly);
    } else {
      collectElementary(ElemType::Bool);
    }
  }

  static std::optional<Symbol> symbolFor(const bc::Module& m, std::string_view name, const bc::VarRef& r) {
    Symbol s;
    s.name = std::string(name);
    s.flags = r.readOnly ? kSymbolFlagReadOnly : 0;
    if (r.bit >= 0) {
      // A single bit (located %IX/%QX/%MX BOOL, or WORD.n): addressed in its area's bit group.
      struct Area {
        const bc::ProcessArea& area;
        IndexGroup bits;
      };
      for (const Area& a : {Area{m.inputs, IndexGroup::InputBits}, Area{m.outputs, IndexGroup::OutputBits},
                            Area{m.memory, IndexGroup::MemoryBits}}) {
        if (r.address < a.area.address || r.address - a.area.address >= a.area.size) continue;
        s.type = "BOOL";
        s.indexGroup = static_cast<uint32_t>(a.bits);
        s.indexOffset = (r.address - a.area.address) * 8 + static_cast<uint32_t>(r.bit);
        s.size = 1;
        s.adsType = adst::kBit;
        s.flags |= kSymbolFlagBitValue;
        return s;
      }
      return std::nullopt;
    }
    if (r.type >= m.types.size()) return std::nullopt;
    const bc::TypeDesc& t = m.types[r.type];
    s.type = t.name;
    s.indexGroup = static_cast<uint32_t>(IndexGroup::DataBytes);
    s.indexOffset = r.address;
    s.size = t.size;
    s.adsType = adsTypeOf(m, r.type);
    return s;
  }

  std::vector<Symbol> takeSymbols() { return std::move(symbols_); }
  std::vector<DataType> takeTypes() { return std::move(types_); }
  std::vector<ByteRange> takeReadOnly() { return std::move(readOnly_); }

 private:
  bool firstTime(const std::string& name) { return seen_.insert(lowerCase(name)).second; }

  void collectElementary(ElemType e) {
    const auto& info = elemTypeInfo(e);
    std::string name(info.name);
    if (!firstTime(name)) return;
    types_.push_back(DataType{name, "", info.sizeBytes, ads::adsTypeOf(e), kTypeFlagDataType, {}, {}, {}});
  }

  void collectType(bc::TypeId id) {
    if (id >= m_.types.size()) return;
    const bc::TypeDesc& t = m_.types[id];
    if (!firstTime(t.name)) return;
    DataType d{t.name, "", t.size, adsTypeOf(m_, id), kTypeFlagDataType, {}, {}, {}};
    switch (t.kind) {
      case bc::TypeKind::Array:
        if (t.element >= m_.types.size()) return;
        d.baseType = m_.types[t.element].name;
        for (const bc::ArrayDim& dim : t.dims) d.dims.push_back({static_cast<int32_t>(dim.lo), static_cast<uint32_t>(dim.count())});
        types_.push_back(std::move(d));
        collectType(t.element);
        return;
      case bc::TypeKind::Struct:
        for (const bc::Field& f : t.fields) {
          if (!isMember(f) || f.type >= m_.types.size()) continue;
          d.members.push_back({f.name, m_.types[f.type].name, m_.types[f.type].size, f.offset, adsTypeOf(m_, f.type)});
        }
        types_.push_back(std::move(d));
        for (const bc::Field& f : t.fields)
          if (isMember(f)) collectType(f.type);
        return;
      case bc::TypeKind::Enum:
        d.baseType = std::string(elemTypeInfo(t.elem).name);
        d.flags |= kTypeFlagEnumInfos;
        for (const bc::Enumerator& e : t.enumerators) d.enumerators.push_back({e.name, e.value});
        types_.push_back(std::move(d));
        collectElementary(t.elem);
        return;
      default: types_.push_back(std::move(d)); return;
    }
  }

  // CONSTANTs and {attribute 'ads_readonly'} variables, down through struct members.
  void collectReadOnly(bc::TypeId id, uint32_t address, bool readOnly) {
    if (id >= m_.types.size()) return;
    const bc::TypeDesc& t = m_.types[id];
    if (readOnly) {
      readOnly_.push_back({address, t.size});
      return;
    }
    if (t.kind != bc::TypeKind::Struct) return;
    for (const bc::Field& f : t.fields)
      if (!f.absolute && f.bit < 0) collectReadOnly(f.type, address + f.offset, f.readOnly);
  }

  const bc::Module& m_;
  std::vector<Symbol> symbols_;
  std::vector<DataType> types_;
  std::vector<ByteRange> readOnly_;
  std::unordered_set<std::string> seen_;
};

}  // namespace

SymbolTable buildSymbolTable(const bc::Module& m) {
  Builder b(m);
  for (const bc::NamedVar& v : bc::listVariables(m)) b.variable(v.name, v.ref.type, v.ref.address, v.ref.bit, v.ref.readOnly);
  MemoryLayout layout;
  layout.dataSize = m.staticSize;
  layout.inputs = {m.inputs.address, m.inputs.size};
  layout.outputs = {m.outputs.address, m.outputs.size};
  layout.memory = {m.memory.address, m.memory.size};
  layout.readOnly = b.takeReadOnly();
  // The null guard and the constant data above the variables are never writable.
  layout.readOnly.push_back({0, bc::Module::kNullGuard});
  if (m.writableEnd < m.staticSize) layout.readOnly.push_back({m.writableEnd, m.staticSize - m.writableEnd});
  auto resolver = [&m](std::string_view path) -> std::optional<Symbol> {
    auto ref = bc::resolveVariable(m, path);
    if (!ref) return std::nullopt;
    return Builder::symbolFor(m, path, *ref);
  };
  return SymbolTable(b.takeSymbols(), b.takeTypes(), std::move(layout), resolver);
}

uint32_t adsTypeOf(ElemType e) {
  switch (e) {
    case ElemType::Bool: return adst::kBit;
    case ElemType::Byte:
    case ElemType::Usint:
    case ElemType::Char: return adst::kUint8;
    case ElemType::Word:
    case ElemType::Uint:
    case ElemType::Wchar: return adst::kUint16;
    case ElemType::Dword:
    case ElemType::Udint:
    case ElemType::Time:
    case ElemType::Date:
    case ElemType::Tod:
    case ElemType::Dt: return adst::kUint32;
    case ElemType::Lword:
    case ElemType::Ulint:
    case ElemType::Ltime:
    case ElemType::Ldate:
    case ElemType::Ltod:
    case ElemType::Ldt: return adst::kUint64;
    case ElemType::Sint: return adst::kInt8;
    case ElemType::Int: return adst::kInt16;
    case ElemType::Dint: return adst::kInt32;
    case ElemType::Lint: return adst::kInt64;
    case ElemType::Real: return adst::kReal32;
    case ElemType::Lreal: return adst::kReal64;
    case ElemType::String: return adst::kString;
    case ElemType::Wstring: return adst::kWstring;
  }
  return adst::kVoid;
}

}  // namespace virtcom::proto::ads
