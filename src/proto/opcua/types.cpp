#include "proto/opcua/types.hpp"

#include <charconv>
#include <cstdio>

namespace virtcom::proto::opcua {

const char* builtinTypeName(BuiltinType t) {
  switch (t) {
#define X(name, id, cpp) \
  case BuiltinType::name: return #name;
#include "proto/opcua/builtin_types.def"
#undef X
    case BuiltinType::Null: break;
  }
  return "Null";
}

std::string statusName(uint32_t code) {
  switch (static_cast<StatusCodeValue>(code)) {
#define X(name, value) \
  case StatusCodeValue::name: return #name;
#include "proto/opcua/status_codes.def"
#undef X
  }
  char text[16];
  std::snprintf(text, sizeof text, "0x%08x", code);
  return text;
}

std::string formatNodeId(const NodeId& id) {
  std::string out = id.ns ? "ns=" + std::to_string(id.ns) + ";" : "";
  switch (id.kind) {
    case NodeId::Kind::Numeric: return out + "i=" + std::to_string(id.numeric);
    case NodeId::Kind::String: return out + "s=" + id.text;
    case NodeId::Kind::Guid: {
      char g[40];
      const auto& d = id.guid.data4;
      std::snprintf(g, sizeof g, "%08X-%04X-%04X-%02X%02X-%02X%02X%02X%02X%02X%02X", id.guid.data1, id.guid.data2,
                    id.guid.data3, d[0], d[1], d[2], d[3], d[4], d[5], d[6], d[7]);
      return out + "g=" + g;
    }
    case NodeId::Kind::Opaque: {
      std::string hex;
      char b[3];
      for (unsigned char c : id.text) {
        std::snprintf(b, sizeof b, "%02x", c);
        hex += b;
      }
      return out + "b=" + hex;
    }
  }
  return out;
}

std::optional<NodeId> parseNodeId(std::string_view text) {
  auto number = [](std::string_view digits, uint32_t limit) -> std::optional<uint32_t> {
    uint32_t v = 0;
    auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
    if (digits.empty() || error != std::errc{} || end != digits.data() + digits.size() || v > limit) return std::nullopt;
    return v;
  };
  uint16_t ns = 0;
  if (text.starts_with("ns=")) {
    const size_t semi = text.find(';');
    auto n = semi == std::string_view::npos ? std::nullopt : number(text.substr(3, semi - 3), 0xFFFF);
    if (!n) return std::nullopt;
    ns = static_cast<uint16_t>(*n);
    text.remove_prefix(semi + 1);
  }
  if (text.starts_with("i=")) {
    auto id = number(text.substr(2), UINT32_MAX);
    if (!id) return std::nullopt;
    return NodeId::num(ns, *id);
  }
  if (text.starts_with("s=") && text.size() > 2) return NodeId::str(ns, std::string(text.substr(2)));
  return std::nullopt;
}

Variant Variant::scalar(Scalar s) {
  Variant v;
  v.type = static_cast<BuiltinType>(s.index());
  if (s.index() != 0) v.values.push_back(std::move(s));
  return v;
}

bool DiagnosticInfo::operator==(const DiagnosticInfo& o) const {
  bool sameInner = inner == o.inner || (inner && o.inner && *inner == *o.inner);
  return symbolicId == o.symbolicId && namespaceUri == o.namespaceUri && localizedText == o.localizedText &&
         locale == o.locale && additionalInfo == o.additionalInfo && hasAdditionalInfo == o.hasAdditionalInfo &&
         hasInnerStatus == o.hasInnerStatus && innerStatus == o.innerStatus && sameInner;
}

}  // namespace virtcom::proto::opcua
