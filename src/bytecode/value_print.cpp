// formatValue: the IEC literal text of a value in the memory image (monitoring, CLI --print);
// the inverse of value_parse.cpp.
#include <cstdio>
#include <cstring>

#include "bytecode/module.hpp"

namespace virtcom::bc {

namespace {

uint64_t loadUnsigned(const uint8_t* p, uint32_t size) {
  uint64_t v = 0;
  for (uint32_t i = 0; i < size && i < 8; ++i) v |= uint64_t{p[i]} << (8 * i);
  return v;
}

int64_t loadSigned(const uint8_t* p, uint32_t size) {
  const uint64_t v = loadUnsigned(p, size);
  if (size == 0 || size >= 8) return static_cast<int64_t>(v);
  const unsigned shift = 64 - 8 * size;
  return static_cast<int64_t>(v << shift) >> shift;
}

class Formatter {
 public:
  Formatter(const Module& m, const uint8_t* memory) : m_(m), mem_(memory) {}

  void value(TypeId type, uint64_t address, int bit) {
    if (bit >= 0) {
      if (!inside(address, 1)) return unreadable();
      out_ += (mem_[address] >> (bit & 7)) & 1 ? "TRUE" : "FALSE";
      return;
    }
    if (type >= m_.types.size()) return unreadable();
    const TypeDesc& t = m_.types[type];
    if (!inside(address, t.size)) return unreadable();
    switch (t.kind) {
      case TypeKind::Elementary: return elementary(t, mem_ + address);
      case TypeKind::String: return text(t, mem_ + address);
      case TypeKind::Enum: return enumeration(t, mem_ + address);
      case TypeKind::Array: return array(t, address);
      case TypeKind::Struct: return structure(t, address);
      case TypeKind::Pointer:
      case TypeKind::Reference: return hex(loadUnsigned(mem_ + address, t.size ? t.size : 4));
    }
  }

  std::string take() { return std::move(out_); }

 private:
  bool inside(uint64_t address, uint64_t size) const {
    return address <= m_.memorySize() && size <= m_.memorySize() - address;
  }
  void unreadable() { out_ += "?"; }

  void hex(uint64_t v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "16#%llX", static_cast<unsigned long long>(v));
    out_ += buf;
  }

  void elementary(const TypeDesc& t, const uint8_t* p) {
    const uint32_t size = elemTypeInfo(t.elem).sizeBytes;
    switch (t.elem) {
      case ElemType::Bool: out_ += *p ? "TRUE" : "FALSE"; return;
      case ElemType::Real: {
        float f;
        std::memcpy(&f, p, 4);
        out_ += formatReal(f);
        return;
      }
      case ElemType::Lreal: {
        double d;
        std::memcpy(&d, p, 8);
        out_ += formatLreal(d);
        return;
      }
      case ElemType::Time: out_ += formatTimeMs(loadSigned(p, 4)); return;
      case ElemType::Ltime: out_ += formatLtimeNs(loadSigned(p, 8)); return;
      case ElemType::Date: out_ += formatDate(static_cast<int64_t>(loadUnsigned(p, 4))); return;
      case ElemType::Tod: out_ += formatTimeOfDay(static_cast<int64_t>(loadUnsigned(p, 4))); return;
      case ElemType::Dt: out_ += formatDateAndTime(static_cast<int64_t>(loadUnsigned(p, 4))); return;
      case ElemType::Ldate: out_ += formatLdate(loadSigned(p, 8)); return;
      case ElemType::Ltod: out_ += formatLtod(loadSigned(p, 8)); return;
      case ElemType::Ldt: out_ += formatLdt(loadSigned(p, 8)); return;
      case ElemType::Char: out_ += quoteString(std::string_view(reinterpret_cast<const char*>(p), 1)); return;
      case ElemType::Wchar:
        out_ += '"';
        wideChar(static_cast<unsigned>(loadUnsigned(p, 2)));
        out_ += '"';
        return;
      case ElemType::String:
      case ElemType::Wstring: return text(t, p);
      default: break;
    }
    if (isSignedInt(t.elem))
      out_ += std::to_string(loadSigned(p, size));
    else
      out_ += std::to_string(loadUnsigned(p, size));
  }

  // STRING(n): up to the NUL or n characters. WSTRING(n): UTF-16LE units, non-ASCII as $hhhh.
  void text(const TypeDesc& t, const uint8_t* p) {
    uint32_t cap = t.stringLength;
    if (t.elem == ElemType::Wstring) {
      if (cap == 0 && t.size >= 2) cap = t.size / 2 - 1;
      out_ += '"';
      for (uint32_t i = 0; i < cap; ++i) {
        const unsigned unit = p[2 * i] | (p[2 * i + 1] << 8);
        if (unit == 0) break;
        wideChar(unit);
      }
      out_ += '"';
      return;
    }
    if (cap == 0 && t.size >= 1) cap = t.size - 1;
    const void* nul = std::memchr(p, 0, cap);
    const size_t len = nul ? static_cast<const uint8_t*>(nul) - p : cap;
    out_ += quoteString(std::string_view(reinterpret_cast<const char*>(p), len));
  }

  void wideChar(unsigned unit) {
    char buf[8];
    switch (unit) {
      case '"': out_ += "$\""; return;
      case '$': out_ += "$$"; return;
      case '\n': out_ += "$N"; return;
      case '\r': out_ += "$R"; return;
      case '\t': out_ += "$T"; return;
      default: break;
    }
    if (unit >= 0x20 && unit < 0x7f) {
      out_ += static_cast<char>(unit);
    } else {
      std::snprintf(buf, sizeof buf, "$%04X", unit);
      out_ += buf;
    }
  }

  void enumeration(const TypeDesc& t, const uint8_t* p) {
    const uint32_t size = t.size ? t.size : elemTypeInfo(t.elem).sizeBytes;
    const int64_t v = isSignedInt(t.elem) ? loadSigned(p, size) : static_cast<int64_t>(loadUnsigned(p, size));
    for (const Enumerator& e : t.enumerators) {
      if (e.value == v) {
        out_ += t.name + "#" + e.name;
        return;
      }
    }
    out_ += std::to_string(v);
  }

  // Arrays print flat in row-major order, as an IEC array initialiser.
  void array(const TypeDesc& t, uint64_t address) {
    if (t.element >= m_.types.size()) return unreadable();
    uint64_t count = 1;
    for (const ArrayDim& d : t.dims) count *= d.count();
    const uint64_t step = m_.types[t.element].size;
    out_ += '[';
    for (uint64_t i = 0; i < count; ++i) {
      if (i) out_ += ", ";
      value(t.element, address + i * step, -1);
    }
    out_ += ']';
  }

  void structure(const TypeDesc& t, uint64_t address) {
    out_ += '(';
    bool first = true;
    for (const Field& f : t.fields) {
      if (f.hidden) continue;
      if (!first) out_ += ", ";
      first = false;
      out_ += f.name + " := ";
      const uint64_t at = (f.absolute ? 0 : address) + f.offset + (f.bit >= 0 ? f.bit / 8 : 0);
      value(f.type, at, f.bit >= 0 ? f.bit % 8 : -1);
    }
    out_ += ')';
  }

  const Module& m_;
  const uint8_t* mem_;
  std::string out_;
};

}  // namespace

std::string formatValue(const Module& m, const VarRef& ref, const uint8_t* memory) {
  Formatter f(m, memory);
  f.value(ref.type, ref.address, ref.bit);
  return f.take();
}

}  // namespace virtcom::bc
