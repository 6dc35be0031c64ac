#include "proto/opcua/plc_values.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace virtcom::proto::opcua {

namespace {

// WSTRING's UTF-16LE (up to its NUL) as UTF-8, appended to a String on the wire.
void encodeWide(Writer& w, std::span<const uint8_t> bytes) {
  const size_t lengthAt = w.size();
  w.i32(0);
  uint32_t written = 0;
  auto put = [&](uint8_t b) {
    w.u8(b);
    ++written;
  };
  for (size_t i = 0; i + 1 < bytes.size(); i += 2) {
    uint32_t c = bytes[i] | (uint32_t{bytes[i + 1]} << 8);
    if (c == 0) break;
    if (c >= 0xD800 && c < 0xDC00 && i + 3 < bytes.size()) {
      uint32_t low = bytes[i + 2] | (uint32_t{bytes[i + 3]} << 8);
      if (low >= 0xDC00 && low < 0xE000) {
        c = 0x10000 + ((c - 0xD800) << 10) + (low - 0xDC00);
        i += 2;
      }
    }
    if (c < 0x80) {
      put(static_cast<uint8_t>(c));
    } else if (c < 0x800) {
      put(static_cast<uint8_t>(0xC0 | (c >> 6)));
      put(static_cast<uint8_t>(0x80 | (c & 0x3F)));
    } else if (c < 0x10000) {
      put(static_cast<uint8_t>(0xE0 | (c >> 12)));
      put(static_cast<uint8_t>(0x80 | ((c >> 6) & 0x3F)));
      put(static_cast<uint8_t>(0x80 | (c & 0x3F)));
    } else {
      put(static_cast<uint8_t>(0xF0 | (c >> 18)));
      put(static_cast<uint8_t>(0x80 | ((c >> 12) & 0x3F)));
      put(static_cast<uint8_t>(0x80 | ((c >> 6) & 0x3F)));
      put(static_cast<uint8_t>(0x80 | (c & 0x3F)));
    }
  }
  w.put32(lengthAt, written);
}

// UTF-8 to UTF-16LE code units; invalid sequences become U+FFFD.
void toUtf16(std::string_view s, std::vector<uint16_t>& out) {
  for (size_t i = 0; i < s.size();) {
    const auto b = static_cast<uint8_t>(s[i]);
    uint32_t c = 0xFFFD;
    size_t n = b < 0x80 ? 1 : (b >> 5) == 0x6 ? 2 : (b >> 4) == 0xE ? 3 : (b >> 3) == 0x1E ? 4 : 0;
    if (n == 0 || i + n > s.size()) {
      ++i;
    } else {
      c = n == 1 ? b : b & (0xFF >> (n + 1));
      for (size_t k = 1; k < n; ++k) c = (c << 6) | (static_cast<uint8_t>(s[i + k]) & 0x3F);
      i += n;
    }
    if (c >= 0x10000) {
      c -= 0x10000;
      out.push_back(static_cast<uint16_t>(0xD800 + (c >> 10)));
      out.push_back(static_cast<uint16_t>(0xDC00 + (c & 0x3FF)));
    } else {
      out.push_back(static_cast<uint16_t>(c));
    }
  }
}

void encodeElement(Writer& w, const PlcValue& v, std::span<const uint8_t> bytes) {
  switch (v.type) {
    case BuiltinType::Boolean: w.u8(v.bit >= 0 ? (bytes[0] >> v.bit) & 1 : bytes[0] != 0); return;
    case BuiltinType::String: {
      if (v.wide) return encodeWide(w, bytes);
      auto end = std::find(bytes.begin(), bytes.end(), uint8_t{0});
      w.i32(static_cast<int32_t>(end - bytes.begin()));
      w.raw(bytes.first(static_cast<size_t>(end - bytes.begin())));
      return;
    }
    default: w.raw(bytes); return;
  }
}

double numberAt(const PlcValue& v, std::span<const uint8_t> b) {
  auto get = [&b]<class T>(T) {
    T x;
    std::memcpy(&x, b.data(), sizeof x);
    return static_cast<double>(x);
  };
  switch (v.type) {
    case BuiltinType::SByte: return get(int8_t{});
    case BuiltinType::Byte: return get(uint8_t{});
    case BuiltinType::Int16: return get(int16_t{});
    case BuiltinType::UInt16: return get(uint16_t{});
    case BuiltinType::Int32: return get(int32_t{});
    case BuiltinType::UInt32: return get(uint32_t{});
    case BuiltinType::Int64: return get(int64_t{});
    case BuiltinType::UInt64: return get(uint64_t{});
    case BuiltinType::Float: return get(float{});
    case BuiltinType::Double: return get(double{});
    default: return 0;
  }
}

}  // namespace

void encodePlcVariant(Writer& w, const PlcValue& v, std::span<const uint8_t> image) {
  uint8_t mask = static_cast<uint8_t>(v.type);
  if (v.isArray) mask |= kVariantArray;
  if (v.dims.size() > 1) mask |= kVariantDimensions;
  w.u8(mask);
  if (v.isArray) w.i32(static_cast<int32_t>(v.count));
  for (uint32_t i = 0; i < v.count; ++i) encodeElement(w, v, image.subspan(v.offset + i * v.elementSize, v.elementSize));
  if (mask & kVariantDimensions) {
    w.i32(static_cast<int32_t>(v.dims.size()));
    for (uint32_t d : v.dims) w.i32(static_cast<int32_t>(d));
  }
}

bool plcValueChanged(const PlcValue& v, std::span<const uint8_t> before, std::span<const uint8_t> now, double deadband) {
  const size_t size = size_t{v.elementSize} * v.count;
  auto a = before.subspan(v.offset, size), b = now.subspan(v.offset, size);
  if (v.bit >= 0) return ((a[0] ^ b[0]) >> v.bit) & 1;
  if (deadband > 0 && !v.isArray && v.type != BuiltinType::Boolean && v.type != BuiltinType::String)
    return std::fabs(numberAt(v, b) - numberAt(v, a)) > deadband;
  return !std::equal(a.begin(), a.end(), b.begin());
}

uint32_t plcBytesOf(const Variant& value, const PlcValue& v, std::vector<uint8_t>& out) {
  constexpr auto kMismatch = static_cast<uint32_t>(StatusCodeValue::BadTypeMismatch);
  if (value.type != v.type || value.isArray != v.isArray || value.values.size() != v.count) return kMismatch;
  out.assign(size_t{v.elementSize} * v.count, 0);
  std::vector<uint8_t> scratch;
  for (uint32_t i = 0; i < v.count; ++i) {
    uint8_t* at = out.data() + size_t{i} * v.elementSize;
    const Scalar& s = value.values[i];
    if (v.type == BuiltinType::String) {
      const std::string& text = std::get<String>(s).text;
      if (v.wide) {
        std::vector<uint16_t> units;
        toUtf16(text, units);
        if ((units.size() + 1) * 2 > v.elementSize) return static_cast<uint32_t>(StatusCodeValue::BadOutOfRange);
        for (size_t k = 0; k < units.size(); ++k) {
          at[2 * k] = static_cast<uint8_t>(units[k]);
          at[2 * k + 1] = static_cast<uint8_t>(units[k] >> 8);
        }
      } else {
        if (text.size() + 1 > v.elementSize) return static_cast<uint32_t>(StatusCodeValue::BadOutOfRange);
        std::memcpy(at, text.data(), text.size());
      }
      continue;
    }
    scratch.clear();
    Writer w(scratch);
    encodeScalar(w, s);
    if (v.type == BuiltinType::Boolean) {
      at[0] = scratch[0] ? 1 : 0;
      continue;
    }
    if (scratch.size() != v.elementSize) return kMismatch;
    std::memcpy(at, scratch.data(), scratch.size());
  }
  return 0;
}

}  // namespace virtcom::proto::opcua
