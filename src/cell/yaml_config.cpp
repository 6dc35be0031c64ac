// The cell file's YAML through libyaml's event parser (C, Debian libyaml-dev): a 128-station cell
// (4,000 lines) loads several times faster than through yaml-cpp's node API, which spent most
// of the start-up in its scanner. Scalars stay text (the ConfigReader types them with units).
#include "cell/yaml_config.hpp"

#include <yaml.h>

#include <map>
#include <memory>
#include <optional>
#include <string>

#include "core/cell_diagnostic_codes.hpp"

namespace virtcom::cell {

namespace {

SourceLocation at(uint32_t fileId, const yaml_mark_t& m) {
  return {fileId, static_cast<uint32_t>(m.line + 1), static_cast<uint32_t>(m.column + 1)};
}

// Plain `~`, `null` and empty values are YAML's null: an empty scalar, as for `key:`.
bool isPlainNull(const yaml_event_t& e) {
  if (e.data.scalar.style != YAML_PLAIN_SCALAR_STYLE) return false;
  std::string_view v(reinterpret_cast<const char*>(e.data.scalar.value), e.data.scalar.length);
  return v.empty() || v == "~" || v == "null" || v == "Null" || v == "NULL";
}

// Builds the tree from the event stream: one node per call, recursively, at most kMaxNesting
// sequences and mappings deep (deeper input, such as 3,000 `{` in a row, would exhaust the stack
// here and when the tree is destroyed; no cell, mapping, routes or scenario file comes near it).
// The first syntax error stops it (libyaml cannot go on after one). A duplicate key is reported (C003) and the build goes
// on, so every duplicate of the file comes out of one load; YAML 1.2 requires unique keys and
// silently keeping the first would hide the second value from the user.
class TreeBuilder {
 public:
  static constexpr int kMaxNesting = 256;

  TreeBuilder(yaml_parser_t& parser, uint32_t fileId, Diagnostics& diags)
      : parser_(parser), fileId_(fileId), diags_(diags) {}

  // The first document's root; false on a syntax error (then error()/errorAt() tell).
  bool document(ConfigNode& out) {
    yaml_event_type_t type;
    do {
      if (!next()) return false;
      type = event_.type;
      if (type == YAML_STREAM_END_EVENT) {  // no document at all
        out = ConfigNode::makeScalar("", at(fileId_, event_.start_mark));
        return true;
      }
    } while (type != YAML_DOCUMENT_START_EVENT);
    if (!next()) return false;
    return node(out);
  }

  std::string error() const {
    if (tooDeepAt_) return "sequences and mappings nested more than " + std::to_string(kMaxNesting) + " deep";
    return parser_.problem ? parser_.problem : "unreadable YAML";
  }
  SourceLocation errorAt() const { return tooDeepAt_ ? *tooDeepAt_ : at(fileId_, parser_.problem_mark); }

  ~TreeBuilder() { yaml_event_delete(&event_); }

 private:
  bool next() {
    yaml_event_delete(&event_);
    return yaml_parser_parse(&parser_, &event_) != 0;
  }

  // The node whose first event is the current one.
  bool node(ConfigNode& out) {
    SourceLocation loc = at(fileId_, event_.start_mark);
    switch (event_.type) {
      case YAML_SCALAR_EVENT: {
        out = ConfigNode::makeScalar(isPlainNull(event_) ? std::string()
                                                         : std::string(reinterpret_cast<const char*>(event_.data.scalar.value),
                                                                       event_.data.scalar.length),
                                     loc);
        remember(event_.data.scalar.anchor, out);
        return true;
      }
      case YAML_ALIAS_EVENT: {
        auto it = anchors_.find(reinterpret_cast<const char*>(event_.data.alias.anchor));
        out = it != anchors_.end() ? it->second : ConfigNode::makeScalar("", loc);
        return true;
      }
      case YAML_SEQUENCE_START_EVENT:
      case YAML_MAPPING_START_EVENT: {
        if (depth_ == kMaxNesting) {
          tooDeepAt_ = loc;
          return false;
        }
        ++depth_;
        const bool ok = event_.type == YAML_SEQUENCE_START_EVENT ? sequence(loc, out) : mapping(loc, out);
        --depth_;
        return ok;
      }
      default: out = ConfigNode::makeScalar("", loc); return true;
    }
  }

  bool sequence(SourceLocation loc, ConfigNode& out) {
    std::string anchor = anchorOf(event_.data.sequence_start.anchor);
    out = ConfigNode::makeList(loc);
    for (;;) {
      if (!next()) return false;
      if (event_.type == YAML_SEQUENCE_END_EVENT) break;
      ConfigNode item;
      if (!node(item)) return false;
      out.push(std::move(item));
    }
    if (!anchor.empty()) anchors_[anchor] = out;
    return true;
  }

  bool mapping(SourceLocation loc, ConfigNode& out) {
    std::string anchor = anchorOf(event_.data.mapping_start.anchor);
    out = ConfigNode::makeMap(loc);
    for (;;) {
      if (!next()) return false;
      if (event_.type == YAML_MAPPING_END_EVENT) break;
      ConfigNode key, value;
      if (!node(key) || !next() || !node(value)) return false;
      if (key.kind() == ConfigNode::Kind::Scalar) rejectDuplicate(out, key);
      out.add(key.kind() == ConfigNode::Kind::Scalar ? key.scalar() : std::string(), key.loc(), std::move(value));
    }
    if (!anchor.empty()) anchors_[anchor] = out;
    return true;
  }

  void rejectDuplicate(const ConfigNode& map, const ConfigNode& key) {
    if (!map.has(key.scalar())) return;
    SourceLocation first = map.keyLoc(key.scalar());
    diags_.error(celldiag::C003, key.loc(),
                 "duplicate key '" + key.scalar() + "' (first at line " + std::to_string(first.line) + ", column " +
                     std::to_string(first.col) + "; a key may appear once per mapping)");
  }

  static std::string anchorOf(const yaml_char_t* anchor) { return anchor ? reinterpret_cast<const char*>(anchor) : ""; }
  void remember(const yaml_char_t* anchor, const ConfigNode& n) {
    if (anchor) anchors_[anchorOf(anchor)] = n;
  }

  yaml_parser_t& parser_;
  uint32_t fileId_;
  Diagnostics& diags_;
  yaml_event_t event_{};
  std::map<std::string, ConfigNode> anchors_;
  int depth_ = 0;                          // sequences and mappings open around the current node
  std::optional<SourceLocation> tooDeepAt_;  // where nesting passed kMaxNesting
};

}  // namespace

bool parseYaml(const std::string& path, const std::string& text, SourceManager& sources, Diagnostics& diags,
               ConfigNode& out) {
  uint32_t fileId = sources.addFile(path, text);
  yaml_parser_t parser;
  yaml_parser_initialize(&parser);
  std::unique_ptr<yaml_parser_t, void (*)(yaml_parser_t*)> owner(&parser, yaml_parser_delete);
  yaml_parser_set_input_string(&parser, reinterpret_cast<const unsigned char*>(text.data()), text.size());
  TreeBuilder builder(parser, fileId, diags);
  size_t errorsBefore = diags.errorCount();
  if (builder.document(out)) return diags.errorCount() == errorsBefore;
  diags.error(celldiag::C001, builder.errorAt(), "YAML syntax error: " + builder.error());
  return false;
}

}  // namespace virtcom::cell
