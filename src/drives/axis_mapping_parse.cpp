// parseMapping(): reads and validates a mapping file (format: docs/universal-axis.md, "Mapping files").
// Load time only; every problem becomes a diagnostic at its file position.
#include <algorithm>
#include <cstdlib>
#include <limits>
#include <string>

#include "core/cell_diagnostic_codes.hpp"
#include "drives/axis_mapping.hpp"
#include "drives/normalisation.hpp"

namespace virtcom::drives {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string wordNames(TelegramId t, Dir d) {
  std::string s;
  for (const auto& w : words(t, d)) s += (s.empty() ? "" : ", ") + std::string(w.name);
  return s;
}

bool parseUint(std::string_view text, uint32_t& out) {
  if (text.empty() || text.size() > 10) return false;
  int base = 10;
  if (text.size() > 2 && text[0] == '0' && (text[1] == 'b' || text[1] == 'x')) {
    base = text[1] == 'b' ? 2 : 16;
    text.remove_prefix(2);
  }
  const std::string s(text);
  char* end = nullptr;
  const unsigned long v = std::strtoul(s.c_str(), &end, base);
  if (*end != '\0' || v > 0xffffffffu) return false;
  out = static_cast<uint32_t>(v);
  return true;
}

struct Target {
  WordBits at;
  bool wholeWord = true;
};

class Parser {
 public:
  Parser(Diagnostics& diags, MappingSpec& spec) : diags_(diags), spec_(spec) {}

  bool parse(const ConfigNode& root) {
    ConfigReader cfg(root, diags_, "the mapping file");
    const std::string key = cfg.requireString("telegram");
    if (auto t = findTelegram(key)) {
      spec_.telegram = *t;
      spec_.order = telegram(*t).order;
    } else {
      // An empty value (e.g. only a YAML tag) is not reported by requireString: say it here.
      if (!key.empty() || cfg.ok()) {
        std::string keys;
        for (const auto& t : telegrams()) keys += (keys.empty() ? "" : ", ") + std::string(t.key);
        cfg.error(root.find("telegram")->loc(), "unknown telegram '" + key + "' (expected one of: " + keys + ")");
      }
      return false;
    }
    parseByteOrder(cfg);
    parseParams(cfg);
    if (const ConfigNode* n = mapNode(cfg, "block_inputs")) parseBlockInputs(*n);
    if (const ConfigNode* n = mapNode(cfg, "outputs")) parseSection(*n, Dir::ToDrive);
    if (const ConfigNode* n = mapNode(cfg, "inputs")) parseSection(*n, Dir::FromDrive);
    if (const ConfigNode* n = mapNode(cfg, "sign_of_life")) parseSignOfLife(*n);
    parseUnavailable(cfg);
    cfg.rejectUnknownKeys();
    checkRequired(root);
    // Bit rules first, so a word rule may take its sign from a bit unpacked in the same tick.
    std::stable_partition(spec_.inputs.begin(), spec_.inputs.end(),
                          [](const InputRule& r) { return r.kind == InputRule::Kind::Bit; });
    return cfg.ok() && ok_;
  }

 private:
  void error(SourceLocation loc, std::string message) {
    diags_.error(celldiag::C010, loc, std::move(message));
    ok_ = false;
  }

  const ConfigNode* mapNode(ConfigReader& cfg, const std::string& key) {
    const ConfigNode* n = cfg.child(key);
    if (n && n->kind() != ConfigNode::Kind::Map) {
      error(n->loc(), "'" + key + "' must be a map");
      return nullptr;
    }
    return n;
  }

  void parseByteOrder(ConfigReader& cfg) {
    if (!cfg.has("byte_order")) {
      cfg.child("byte_order");
      return;
    }
    const std::string order = cfg.requireString("byte_order");
    if (order == "big") spec_.order = ByteOrder::Big;
    else if (order == "little") spec_.order = ByteOrder::Little;
    else error(cfg.node().find("byte_order")->loc(), "byte_order must be 'big' (PROFINET) or 'little' (EtherNet/IP), not '" + order + "'");
  }

  void parseParams(ConfigReader& cfg) {
    const ConfigNode* n = mapNode(cfg, "params");
    if (!n) return;
    ConfigReader pr(*n, diags_, "params");
    refSpeed_ = pr.optNumber("ref_speed", 0);
    if (const ConfigNode* ref = n->find("ref_speed"); ref && refSpeed_ > 0)
      spec_.referenceSpeeds.push_back({"params: ref_speed", refSpeed_, ref->loc()});
    polePairs_ = pr.optNumber("pole_pairs", 1);
    pr.rejectUnknownKeys();
    if (!pr.ok()) ok_ = false;
  }

  void parseBlockInputs(const ConfigNode& node) {
    for (const auto& [name, value] : node.entries()) {
      const AxisSignalDef* s = findAxisSignal(name);
      if (!s || s->kind != SignalKind::Config) {
        error(node.keyLoc(name), "'" + name + "' is not a configuration input of UNIVERSAL_AXIS (expected one of: " +
                                     signalNames(SignalKind::Config) + ")");
        continue;
      }
      double v = 0;
      const std::string& text = value.scalar();
      if (s->type == ElemType::Bool && (text == "true" || text == "false")) v = text == "true";
      else if (!number(value, v)) continue;
      spec_.blockInputs.emplace_back(s->id, v);
      if (s->id == AxisSignal::Cfg_RefSpeed && v > 0) spec_.referenceSpeeds.push_back({"Cfg_RefSpeed", v, value.loc()});
      bind(*s, node.keyLoc(name));
    }
  }

  void parseSection(const ConfigNode& node, Dir dir) {
    for (const auto& [key, value] : node.entries()) {
      const SourceLocation keyLoc = node.keyLoc(key);
      if (key == "bits") {
        if (value.kind() != ConfigNode::Kind::Map) {
          error(value.loc(), "'bits' must map signals to bits, e.g. {Control_OFF2: STW1.1}");
          continue;
        }
        for (const auto& [sig, target] : value.entries()) plainBit(sig, value.keyLoc(sig), target, dir);
      } else if (key == "const" && dir == Dir::ToDrive) {
        if (value.kind() != ConfigNode::Kind::Map) {
          error(value.loc(), "'const' must map bits or words to values, e.g. {STW1.10: 1, PZD12: 0}");
          continue;
        }
        for (const auto& [where, v] : value.entries()) constant(where, value.keyLoc(where), v);
      } else if (value.kind() == ConfigNode::Kind::Map && value.has("field") && value.has("encode")) {
        encodedField(key, value, dir);
      } else if (value.kind() == ConfigNode::Kind::Map) {
        rule(key, keyLoc, value, dir);
      } else {
        error(value.loc(), "'" + key + "': expected a map such as {bit: STW1.0} or {word: NSOLL_A}");
      }
    }
  }

  // --- targets -------------------------------------------------------------------------------
  std::optional<Target> target(const ConfigNode& node, Dir dir) {
    if (node.kind() != ConfigNode::Kind::Scalar) {
      error(node.loc(), "expected a word, bit or bit range of the telegram such as STW1.3, NSOLL_A or LogicCommand[4:5]"
                        " (options such as invert go in the signal's own entry: Signal: {bit: STW1.3, invert: true})");
      return std::nullopt;
    }
    return target(node.scalar(), node.loc(), dir);
  }
  std::optional<Target> target(const std::string& text, SourceLocation loc, Dir dir) {
    std::string name = text, rest;
    enum { Word, Bit, Range, S7 } form = Word;
    if (auto sp = text.find(' '); sp != std::string::npos) {
      name = text.substr(0, sp), rest = text.substr(sp + 1), form = S7;
    } else if (auto br = text.find('['); br != std::string::npos) {
      name = text.substr(0, br), rest = text.substr(br), form = Range;
    } else if (auto dot = text.find('.'); dot != std::string::npos) {
      name = text.substr(0, dot), rest = text.substr(dot + 1), form = Bit;
    }
    const auto slot = findWord(spec_.telegram, dir, name);
    if (!slot) {
      error(loc, "unknown " + std::string(dir == Dir::ToDrive ? "output" : "input") + " word '" + name + "' in telegram " +
                     std::string(telegram(spec_.telegram).key) + " (expected one of: " + wordNames(spec_.telegram, dir) + ")");
      return std::nullopt;
    }
    const WordDef& def = word(*slot);
    const uint32_t bits = static_cast<uint32_t>(wireBytes(def.type) * 8);
    Target t;
    t.at.word = slot->index;
    if (form == Word) return t;
    t.wholeWord = false;
    uint32_t lsb = 0, msb = 0;
    bool good = false;
    if (form == Bit) {
      good = parseUint(rest, lsb);
      msb = lsb;
      if (!good && def.layout != Layout::None)
        if (const BitDef* b = findBit(def.layout, rest)) {
          lsb = b->lsb, msb = b->lsb + b->width - 1u, good = true;
        }
    } else if (form == Range) {
      const auto colon = rest.find(':');
      good = rest.back() == ']' && colon != std::string::npos && parseUint(rest.substr(1, colon - 1), lsb) &&
             parseUint(rest.substr(colon + 1, rest.size() - colon - 2), msb) && lsb <= msb;
    } else {  // S7 "byte.bit": byte 0 is the high byte on the wire (spec A.0)
      uint32_t byte = 0, bit = 0;
      const auto dot = rest.find('.');
      good = bits == 16 && dot != std::string::npos && parseUint(rest.substr(0, dot), byte) &&
             parseUint(rest.substr(dot + 1), bit) && byte <= 1 && bit <= 7;
      lsb = msb = (1 - byte) * 8 + bit;
    }
    if (!good || msb >= bits) {
      error(loc, "'" + text + "': expected WORD.bit (0.." + std::to_string(bits - 1) + " or a bit name of " + name +
                     "), WORD[lsb:msb], or the S7 form \"WORD 1.0\" (16-bit words)");
      return std::nullopt;
    }
    t.at.lsb = static_cast<uint8_t>(lsb);
    t.at.width = static_cast<uint8_t>(msb - lsb + 1);
    return t;
  }

  // Marks output bits as written; a bit written twice is an error.
  void claim(Target t, const std::string& owner, SourceLocation loc) {
    const WordDef& def = words(spec_.telegram, Dir::ToDrive)[t.at.word];
    const uint32_t bits = static_cast<uint32_t>(wireBytes(def.type) * 8);
    const uint32_t lo = t.wholeWord ? 0 : t.at.lsb, n = t.wholeWord ? bits : t.at.width;
    for (uint32_t b = lo; b < lo + n; ++b) {
      std::string& prev = owners_[t.at.word][b];
      if (!prev.empty()) {
        error(loc, "bit " + std::string(def.name) + "." + std::to_string(b) + " is written twice: by " + prev + " and by " + owner);
        return;
      }
      prev = owner;
    }
  }

  // --- signals -------------------------------------------------------------------------------
  const AxisSignalDef* signal(const std::string& name, SourceLocation loc, Dir dir) {
    const SignalKind kind = dir == Dir::ToDrive ? SignalKind::Control : SignalKind::Status;
    const AxisSignalDef* s = findAxisSignal(name);
    if (!s || s->kind != kind) {
      error(loc, "'" + name + "' is not a " + (kind == SignalKind::Control ? "Control_*" : "Status_*") +
                     " signal of UNIVERSAL_AXIS (expected one of: " + signalNames(kind) + ")");
      return nullptr;
    }
    return s;
  }

  bool bind(const AxisSignalDef& s, SourceLocation loc) {
    auto& bound = spec_.bound[static_cast<size_t>(s.id)];
    if (bound) {
      error(loc, std::string(s.name) + " is mapped twice");
      return false;
    }
    bound = true;
    return true;
  }

  static std::string signalNames(SignalKind kind) {
    std::string s;
    for (const auto& d : axisSignals())
      if (d.kind == kind) s += (s.empty() ? "" : ", ") + std::string(d.name);
    return s;
  }

  static std::string typeName(ElemType t) { return std::string(elemTypeInfo(t).name); }

  void plainBit(const std::string& name, SourceLocation loc, const ConfigNode& targetNode, Dir dir) {
    const AxisSignalDef* s = signal(name, loc, dir);
    if (!s) return;
    auto t = target(targetNode, dir);
    if (!t || !checkBitTarget(*s, *t, targetNode.loc()) || !bind(*s, loc)) return;
    addBit(*s, *t, loc, false, false, false);
  }

  bool checkBitTarget(const AxisSignalDef& s, Target t, SourceLocation loc) {
    if (s.type != ElemType::Bool) {
      error(loc, std::string(s.name) + " is " + typeName(s.type) + ": map it to a word or a field ({word: ...}), not to one bit");
      return false;
    }
    if (t.wholeWord || t.at.width != 1) {
      error(loc, "width mismatch: " + std::string(s.name) + " is BOOL and needs exactly one bit (WORD.n)");
      return false;
    }
    return true;
  }

  void addBit(const AxisSignalDef& s, Target t, SourceLocation loc, bool invert, bool pulse, bool zeroFirst) {
    if (s.kind == SignalKind::Control) {
      claim(t, std::string(s.name), loc);
      OutputRule r;
      r.kind = OutputRule::Kind::Bit, r.signal = s.id, r.at = t.at;
      r.invert = invert, r.pulseRising = pulse, r.zeroBeforeOne = zeroFirst;
      spec_.outputs.push_back(r);
    } else {
      InputRule r;
      r.kind = InputRule::Kind::Bit, r.signal = s.id, r.at = t.at, r.invert = invert;
      spec_.inputs.push_back(r);
    }
  }

  void rule(const std::string& name, SourceLocation loc, const ConfigNode& node, Dir dir) {
    const AxisSignalDef* s = signal(name, loc, dir);
    if (!s) return;
    ConfigReader r(node, diags_, name);
    const bool isBit = r.has("bit"), isWord = r.has("word") || r.has("field");
    if (isBit == isWord) {
      error(node.loc(), name + ": give exactly one target, `bit:` for BOOL signals or `word:`/`field:` for numbers");
      return;
    }
    const bool invert = r.optBool("invert", false);
    if (isBit) {
      bool pulse = false, zeroFirst = false;
      if (dir == Dir::ToDrive) {
        const std::string p = r.optString("pulse", "");
        if (!p.empty() && p != "rising") error(node.find("pulse")->loc(), "pulse: only 'rising' is supported");
        pulse = p == "rising";
        zeroFirst = r.optBool("requires_zero_before_one", false);
      }
      const ConfigNode* tn = r.child("bit");
      auto t = target(*tn, dir);
      r.rejectUnknownKeys();
      if (!r.ok()) ok_ = false;
      if (!t || !checkBitTarget(*s, *t, tn->loc()) || !bind(*s, loc)) return;
      addBit(*s, *t, loc, invert, pulse, zeroFirst);
      return;
    }
    const ConfigNode* tn = r.child(r.has("word") ? "word" : "field");
    auto t = target(*tn, dir);
    Scale scale = parseScale(r, node);
    int16_t sign = -1;
    const char* signKey = dir == Dir::ToDrive ? "signed_from" : "magnitude_signed_by";
    if (const ConfigNode* sn = r.child(signKey)) {
      const AxisSignalDef* by = findAxisSignal(sn->scalar());
      if (!by || by->type != ElemType::Bool || by->kind != s->kind)
        error(sn->loc(), std::string(signKey) + " needs a BOOL " + (dir == Dir::ToDrive ? "Control_*" : "Status_*") + " signal, not '" + sn->scalar() + "'");
      else sign = static_cast<int16_t>(by->id);
    }
    std::vector<double> clamp;
    if (dir == Dir::ToDrive && r.has("clamp")) clamp = r.requireVector("clamp", Dimension::Dimensionless, 2);
    r.rejectUnknownKeys();
    if (!r.ok()) ok_ = false;
    if (!t || !bind(*s, loc)) return;
    if (s->type == ElemType::Bool) {
      error(tn->loc(), "width mismatch: " + name + " is BOOL: map it to one bit (`bit: WORD.n`)");
      return;
    }
    if (!checkWordWidth(*s, *t, tn->loc(), dir, !clamp.empty())) return;
    if (dir == Dir::ToDrive) {
      claim(*t, name, loc);
      OutputRule o;
      o.kind = OutputRule::Kind::Word, o.signal = s->id, o.at = t->at, o.scale = scale, o.signedFrom = sign;
      rangeOf(*t, o.lo, o.hi);
      if (clamp.size() == 2) o.lo = clamp[0] * 1.0, o.hi = clamp[1] * 1.0;
      spec_.outputs.push_back(o);
    } else {
      InputRule in;
      in.kind = InputRule::Kind::Word, in.signal = s->id, in.at = t->at, in.scale = scale, in.signedBy = sign;
      spec_.inputs.push_back(in);
    }
  }

  // The raw range a word or field can carry.
  void rangeOf(Target t, double& lo, double& hi) const {
    const WordDef& def = words(spec_.telegram, Dir::ToDrive)[t.at.word];
    if (!t.wholeWord) {
      lo = 0, hi = static_cast<double>((uint64_t(1) << t.at.width) - 1);
      return;
    }
    switch (def.type) {
      case WireType::I16: lo = INT16_MIN, hi = INT16_MAX; break;
      case WireType::I32: lo = INT32_MIN, hi = INT32_MAX; break;
      case WireType::F32: lo = -kInf, hi = kInf; break;
      case WireType::Bits32: lo = 0, hi = UINT32_MAX; break;
      default: lo = 0, hi = UINT16_MAX; break;
    }
  }

  // A 32-bit signal into a 16-bit word must say how it is narrowed (`clamp:`); a number never
  // goes into a control/status word as a whole (use a field).
  bool checkWordWidth(const AxisSignalDef& s, Target t, SourceLocation loc, Dir dir, bool clamped) {
    const WordDef& def = words(spec_.telegram, dir)[t.at.word];
    if (t.wholeWord && def.layout != Layout::None) {
      error(loc, std::string(def.name) + " is a bit word: map " + std::string(s.name) + " to a field (" +
                     std::string(def.name) + "[lsb:msb]) or to a numeric word");
      return false;
    }
    const size_t signalBytes = elemTypeInfo(s.type).sizeBytes;
    const size_t targetBits = t.wholeWord ? wireBytes(def.type) * 8 : t.at.width;
    if (dir == Dir::ToDrive && !clamped && def.type != WireType::F32 && signalBytes * 8 > targetBits) {
      error(loc, "width mismatch: " + std::string(s.name) + " is " + typeName(s.type) + " (" + std::to_string(signalBytes * 8) +
                     " bits) but " + std::string(def.name) + " holds " + std::to_string(targetBits) +
                     " bits; add `clamp: [lo, hi]` to say how it is narrowed");
      return false;
    }
    return true;
  }

  Scale parseScale(ConfigReader& r, const ConfigNode& node) {
    Scale s;
    const ConfigNode* n = r.child("scale");
    if (!n) return s;
    if (n->kind() == ConfigNode::Kind::Scalar) {
      const std::string& p = n->scalar();
      const double n2 = kN2Full, n4 = kN4Full;
      if (p == "percent_q14") s = {n2, 100, 0};
      else if (p == "rpm_to_n2" || p == "n2_to_rpm") s = {n2, needRefSpeed(n->loc()), 0};
      else if (p == "rpm_to_n4" || p == "n4_to_rpm") s = {n4, needRefSpeed(n->loc()), 0};
      else if (p == "rpm_to_centiHz" || p == "centiHz_to_rpm") s = {100 * polePairs_, 60, 0};
      else error(n->loc(), "unknown scale '" + p + "' (expected percent_q14, rpm_to_n2, rpm_to_n4, rpm_to_centiHz, n2_to_rpm, "
                           "n4_to_rpm, centiHz_to_rpm, or {num: N, den: D, offset: O})");
      return s;
    }
    ConfigReader sr(*n, diags_, "scale");
    s.num = sr.optNumber("num", 1);
    if (const ConfigNode* d = sr.child("den")) {
      if (d->scalar() == "ref_speed") s.den = needRefSpeed(d->loc());
      else number(*d, s.den);
    }
    s.offset = sr.optNumber("offset", 0);
    sr.rejectUnknownKeys();
    if (!sr.ok()) ok_ = false;
    if (s.num == 0 || s.den == 0) error(node.find("scale")->loc(), "scale: num and den must not be 0");
    return s;
  }

  double needRefSpeed(SourceLocation loc) {
    if (refSpeed_ > 0) return refSpeed_;
    error(loc, "this scale needs `params: {ref_speed: <p2000 in rpm>}`");
    return 1;
  }

  bool number(const ConfigNode& n, double& out) {
    char* end = nullptr;
    out = std::strtod(n.scalar().c_str(), &end);
    if (n.kind() == ConfigNode::Kind::Scalar && !n.scalar().empty() && *end == '\0') return true;
    error(n.loc(), "expected a number, not '" + n.scalar() + "'");
    return false;
  }

  void encodedField(const std::string& label, const ConfigNode& node, Dir dir) {
    if (dir != Dir::ToDrive) {
      error(node.loc(), "encoded fields (`field` + `encode`) are only supported for outputs");
      return;
    }
    ConfigReader r(node, diags_, label);
    const ConfigNode* fn = r.child("field");
    auto t = target(*fn, dir);
    OutputRule o;
    o.kind = OutputRule::Kind::Field;
    if (const ConfigNode* d = r.child("default"))
      if (!parseUint(d->scalar(), o.value)) error(d->loc(), "default: expected a code such as 0b00");
    const ConfigNode* enc = r.child("encode");
    r.rejectUnknownKeys();
    if (!r.ok()) ok_ = false;
    if (!t) return;
    if (t->wholeWord) {
      error(fn->loc(), "'" + fn->scalar() + "': an encoded field needs a bit range, e.g. LogicCommand[4:5]");
      return;
    }
    o.at = t->at;
    const uint32_t maxCode = (1u << t->at.width) - 1u;
    if (o.value > maxCode) error(fn->loc(), "width mismatch: default code does not fit in " + std::to_string(t->at.width) + " bits");
    if (enc->kind() != ConfigNode::Kind::Map) {
      error(enc->loc(), "encode: expected a map {Signal: code, ...}");
      return;
    }
    for (const auto& [sig, codeNode] : enc->entries()) {
      const AxisSignalDef* s = signal(sig, enc->keyLoc(sig), dir);
      if (!s) continue;
      uint32_t code = 0;
      if (s->type != ElemType::Bool) error(enc->keyLoc(sig), sig + " is " + typeName(s->type) + "; encoded fields take BOOL signals");
      else if (!parseUint(codeNode.scalar(), code)) error(codeNode.loc(), "expected a code such as 0b01");
      else if (code > maxCode) error(codeNode.loc(), "width mismatch: code " + codeNode.scalar() + " does not fit in " + std::to_string(t->at.width) + " bits");
      else if (o.codeCount == OutputRule::kMaxCodes) error(codeNode.loc(), "at most 4 signals per encoded field");
      else if (bind(*s, enc->keyLoc(sig))) {
        o.codeSignals[o.codeCount] = s->id;
        o.codes[o.codeCount++] = code;
      }
    }
    claim(*t, label, node.loc());
    spec_.outputs.push_back(o);
  }

  void constant(const std::string& where, SourceLocation loc, const ConfigNode& v) {
    auto t = target(where, loc, Dir::ToDrive);
    uint32_t value = 0;
    if (!parseUint(v.scalar(), value)) {
      error(v.loc(), "const: expected a non-negative value such as 1 or 0x0400");
      return;
    }
    if (!t) return;
    double lo = 0, hi = 0;
    rangeOf(*t, lo, hi);
    if (!t->wholeWord && value > hi) {
      error(v.loc(), "width mismatch: " + v.scalar() + " does not fit in " + std::to_string(t->at.width) + " bit(s)");
      return;
    }
    claim(*t, "const " + where, loc);
    OutputRule o;
    o.kind = OutputRule::Kind::Const, o.at = t->at, o.value = value;
    spec_.outputs.push_back(o);
  }

  void parseSignOfLife(const ConfigNode& node) {
    ConfigReader r(node, diags_, "sign_of_life");
    const std::string out = r.requireString("out");
    r.rejectUnknownKeys();
    if (!r.ok()) {
      ok_ = false;
      return;
    }
    auto t = target(out, node.find("out")->loc(), Dir::ToDrive);
    if (!t) return;
    if (t->wholeWord || t->at.width != 4) {
      error(node.find("out")->loc(), "sign_of_life.out must be a 4-bit field such as STW2[12:15]");
      return;
    }
    claim(*t, "sign_of_life", node.loc());
    spec_.masterSignOfLife = t->at;
  }

  void parseUnavailable(ConfigReader& cfg) {
    const ConfigNode* n = cfg.child("unavailable");
    if (!n) return;
    if (n->kind() != ConfigNode::Kind::List) {
      error(n->loc(), "'unavailable' must be a list of signal names");
      return;
    }
    for (const auto& item : n->items()) {
      const AxisSignalDef* s = findAxisSignal(item.scalar());
      if (!s) error(item.loc(), "'" + item.scalar() + "' is not a signal of UNIVERSAL_AXIS");
      else if (bind(*s, item.loc())) spec_.unavailable[static_cast<size_t>(s->id)] = true;
    }
  }

  void checkRequired(const ConfigNode& root) {
    if (!ok_) return;
    for (const auto& s : axisSignals())
      if (s.required && !spec_.bound[static_cast<size_t>(s.id)])
        error(root.loc(), "missing required signal " + std::string(s.name) + " (" + std::string(s.doc) +
                              "): map it under `inputs:` or list it under `unavailable:`");
    if (!spec_.bound[static_cast<size_t>(AxisSignal::Control_Start)] && !spec_.bound[static_cast<size_t>(AxisSignal::Control_Stop)])
      error(root.loc(), "missing required signal: the drive needs Control_Start or Control_Stop under `outputs:`");
  }

  Diagnostics& diags_;
  MappingSpec& spec_;
  bool ok_ = true;
  double refSpeed_ = 0, polePairs_ = 1;
  std::array<std::array<std::string, 32>, kMaxWords> owners_;
};

}  // namespace

std::optional<MappingSpec> parseMapping(const ConfigNode& root, Diagnostics& diags) {
  MappingSpec spec;
  Parser parser(diags, spec);
  if (!parser.parse(root)) return std::nullopt;
  return spec;
}

}  // namespace virtcom::drives
