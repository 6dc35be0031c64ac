#include "proto/opcua/browse_path.hpp"

#include "proto/opcua/node_ids.hpp"

namespace virtcom::proto::opcua {

namespace {

constexpr std::string_view kExpected = " (expected /NS:NAME elements from the Objects folder, e.g. /4:MAIN/4:x)";

// Characters Annex A.2 reserves: unescaped, they separate or qualify names.
bool reserved(char c) { return c == '/' || c == '.' || c == '<' || c == '>' || c == ':' || c == '#' || c == '!' || c == '&'; }

std::string at(std::string_view text, size_t i) { return "'" + std::string(text) + "' at character " + std::to_string(i + 1) + ": "; }

// The namespace index "NS:" at text[i] if there is one: i moves past it.
std::expected<uint16_t, std::string> readNamespace(std::string_view text, size_t& i) {
  size_t digits = i;
  while (digits < text.size() && text[digits] >= '0' && text[digits] <= '9') ++digits;
  if (digits == i || digits == text.size() || text[digits] != ':') return 0;
  uint32_t ns = 0;
  for (size_t k = i; k < digits; ++k) {
    ns = ns * 10 + static_cast<uint32_t>(text[k] - '0');
    if (ns > 0xFFFF) return std::unexpected(at(text, i) + "namespace index above 65535");
  }
  i = digits + 1;
  return static_cast<uint16_t>(ns);
}

}  // namespace

bool isBrowsePath(std::string_view text) { return text.starts_with('/') || text.starts_with('.'); }

std::expected<std::vector<BrowsePathElement>, std::string> parseBrowsePath(std::string_view text) {
  std::vector<BrowsePathElement> path;
  size_t i = 0;
  while (i < text.size()) {
    BrowsePathElement e;
    if (text[i] != '/' && text[i] != '.') return std::unexpected(at(text, i) + "'/' or '.' expected before a browse name" + std::string(kExpected));
    e.aggregates = text[i++] == '.';
    if (i < text.size() && text[i] == '<')
      return std::unexpected(at(text, i) + "reference types in <...> are not supported; '/' follows hierarchical references, '.' aggregates");
    auto ns = readNamespace(text, i);
    if (!ns) return std::unexpected(ns.error());
    e.name.ns = *ns;
    for (; i < text.size() && text[i] != '/' && text[i] != '.'; ++i) {
      if (text[i] == '&') {
        if (++i == text.size()) return std::unexpected(at(text, i - 1) + "'&' escapes the character after it, and none follows");
      } else if (reserved(text[i])) {
        return std::unexpected(at(text, i) + "'" + text[i] + "' is reserved in a browse name; write it as '&" + text[i] + "'");
      }
      e.name.name += text[i];
    }
    if (e.name.name.empty()) return std::unexpected(at(text, i) + "a browse name is missing" + std::string(kExpected));
    path.push_back(std::move(e));
  }
  if (path.empty()) return std::unexpected("'" + std::string(text) + "': an empty browse path" + std::string(kExpected));
  return path;
}

void encodeBrowsePath(Writer& w, const std::vector<BrowsePathElement>& path) {
  encode(w, NodeId::num(0, ids::kObjectsFolder));
  w.i32(static_cast<int32_t>(path.size()));
  for (const BrowsePathElement& e : path) {
    encode(w, NodeId::num(0, e.aggregates ? ids::kAggregates : ids::kHierarchicalReferences));
    encode(w, false);  // IsInverse
    encode(w, true);   // IncludeSubtypes
    encode(w, e.name);
  }
}

}  // namespace virtcom::proto::opcua
