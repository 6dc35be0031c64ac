#include "cell/hmi_section.hpp"

#include <algorithm>
#include <cctype>

#include "core/cell_diagnostic_codes.hpp"
#include "plant/robot.hpp"

namespace virtcom::cell {

namespace {

constexpr struct {
  const char* name;
  HmiShape::Kind kind;
} kShapeKinds[] = {{"rect", HmiShape::Kind::Rect}, {"circle", HmiShape::Kind::Circle}, {"line", HmiShape::Kind::Line}, {"text", HmiShape::Kind::Text}};

// #rgb, #rrggbb or a CSS colour name (letters only): nothing the page could mistake for markup.
bool validColour(const std::string& c) {
  auto hex = [](char ch) { return std::isxdigit(static_cast<unsigned char>(ch)) != 0; };
  auto alpha = [](char ch) { return std::isalpha(static_cast<unsigned char>(ch)) != 0; };
  if (!c.empty() && c[0] == '#') return (c.size() == 4 || c.size() == 7) && std::all_of(c.begin() + 1, c.end(), hex);
  return !c.empty() && c.size() <= 32 && std::ranges::all_of(c, alpha);
}

// A length the drawing may leave out (the automatic value is kept).
std::optional<double> optLength(ConfigReader& r, const char* key) {
  if (!r.has(key)) {
    r.child(key);  // known key
    return std::nullopt;
  }
  return r.requireQuantity(key, Dimension::Length);
}

class HmiReader {
 public:
  HmiReader(Cell& cell, Diagnostics& diags) : cell_(cell), diags_(diags) {}

  void read(const ConfigNode& node) {
    ConfigReader hmi(node, diags_, "'hmi'");
    if (const ConfigNode* devices = hmi.child("devices")) readDevices(*devices);
    if (const ConfigNode* shapes = hmi.child("shapes")) readShapes(*shapes);
    hmi.rejectUnknownKeys();
  }

 private:
  void readDevices(const ConfigNode& devices) {
    if (devices.kind() != ConfigNode::Kind::Map) {
      diags_.error(celldiag::C010, devices.loc(), "'hmi: devices' must map device names to their placement, e.g. Press: { x: 1200 mm, y: 0 mm }");
      return;
    }
    for (const auto& [name, entry] : devices.entries()) {
      auto it = std::ranges::find_if(cell_.devices, [&](const auto& d) { return d->name() == name; });
      if (it == cell_.devices.end()) {
        diags_.error(celldiag::C040, devices.keyLoc(name), "'hmi: devices' names '" + name + "', but the cell has no such device");
        continue;
      }
      DevicePlacement p;
      p.device = static_cast<size_t>(it - cell_.devices.begin());
      ConfigReader r(entry, diags_, "'hmi: devices: " + name + "'");
      p.x = optLength(r, "x");
      p.y = optLength(r, "y");
      p.w = optLength(r, "w");
      p.h = optLength(r, "h");
      p.label = r.optString("label", "");
      p.group = r.optString("group", "");
      pair(entry, "x", "y", p.x, p.y);
      positive(r, entry, "w", p.w);
      positive(r, entry, "h", p.h);
      if (r.has("base")) {
        std::vector<double> base = r.requireVector("base", Dimension::Length, 2);
        if (!dynamic_cast<const plant::Robot*>(it->get()))
          diags_.error(celldiag::C041, entry.find("base")->loc(), "'base' places a robot's frame, but '" + name + "' is a " + (*it)->type());
        p.baseX = base[0];
        p.baseY = base[1];
      } else {
        r.child("base");
      }
      r.rejectUnknownKeys();
      cell_.hmi.devices.push_back(std::move(p));
    }
  }

  void readShapes(const ConfigNode& shapes) {
    if (shapes.kind() != ConfigNode::Kind::List) {
      diags_.error(celldiag::C010, shapes.loc(), "'hmi: shapes' must be a list, e.g. - { kind: rect, x: 0 mm, y: 0 mm, w: 2 m, h: 1 m }");
      return;
    }
    for (const ConfigNode& entry : shapes.items()) {
      ConfigReader r(entry, diags_, "a shape of 'hmi: shapes'");
      if (!r.ok()) continue;
      HmiShape s;
      const std::string kind = r.requireString("kind");
      const auto* known = std::ranges::find_if(kShapeKinds, [&](const auto& k) { return kind == k.name; });
      if (known == std::end(kShapeKinds)) {
        if (!kind.empty())
          diags_.error(celldiag::C041, entry.find("kind")->loc(), "unknown shape kind '" + kind + "' (expected one of: rect, circle, line, text)");
        continue;
      }
      s.kind = known->kind;
      s.x = r.requireQuantity("x", Dimension::Length);
      s.y = r.requireQuantity("y", Dimension::Length);
      switch (s.kind) {
        case HmiShape::Kind::Rect:
          s.w = r.requireQuantity("w", Dimension::Length);
          s.h = r.requireQuantity("h", Dimension::Length);
          break;
        case HmiShape::Kind::Circle: s.r = r.requireQuantity("r", Dimension::Length); break;
        case HmiShape::Kind::Line:
          s.x2 = r.requireQuantity("x2", Dimension::Length);
          s.y2 = r.requireQuantity("y2", Dimension::Length);
          break;
        case HmiShape::Kind::Text: break;
      }
      s.label = s.kind == HmiShape::Kind::Text ? r.requireString("label") : r.optString("label", "");
      s.colour = r.optString("colour", "");
      if (!s.colour.empty() && !validColour(s.colour))
        diags_.error(celldiag::C041, entry.find("colour")->loc(), "'colour' must be #rgb, #rrggbb or a CSS colour name such as steelblue, found '" + s.colour + "'");
      r.rejectUnknownKeys();
      cell_.hmi.shapes.push_back(std::move(s));
    }
  }

  // A coordinate pair is given whole: half a position is a mistake, not a request to guess.
  void pair(const ConfigNode& entry, const char* a, const char* b, const std::optional<double>& va, const std::optional<double>& vb) {
    if (va.has_value() == vb.has_value()) return;
    const char* given = va ? a : b;
    diags_.error(celldiag::C041, entry.keyLoc(given), std::string("'") + a + "' and '" + b + "' go together: '" + given + "' needs '" +
                                                          (va ? b : a) + "'");
  }

  void positive(ConfigReader& r, const ConfigNode& entry, const char* key, const std::optional<double>& v) {
    if (v && *v <= 0) r.error(entry.find(key)->loc(), std::string("'") + key + "' must be positive");
  }

  Cell& cell_;
  Diagnostics& diags_;
};

}  // namespace

const char* shapeKindName(HmiShape::Kind kind) {
  for (const auto& k : kShapeKinds)
    if (k.kind == kind) return k.name;
  return "rect";
}

void readHmiSection(Cell& cell, const ConfigNode* node, Diagnostics& diags) {
  if (node) HmiReader(cell, diags).read(*node);
}

}  // namespace virtcom::cell
