#pragma once
// The cell file's optional `hmi:` section (docs/cell-file.md, docs/hmi.md): where the web HMI's
// layout view draws devices, with what label and in which group, and static shapes (walls,
// fences, tables) drawn under them, so the plan looks like the real plant. Lengths are metres,
// the cell's top view (x right, y up). Read by the loader, used by src/hmi/layout.*.
#include <optional>
#include <string>
#include <vector>

#include "core/config_node.hpp"

namespace virtcom::cell {

// `hmi: devices: NAME: {...}`. Unset values keep the automatic placement.
struct DevicePlacement {
  size_t device = 0;                 // index into Cell::devices
  std::optional<double> x, y;        // the box's lower-left corner (both or neither)
  std::optional<double> w, h;        // its size
  std::optional<double> baseX, baseY;  // robots: where their frame's origin stands (both or neither)
  std::string label;                 // shown instead of the name; empty: the name
  std::string group;                 // devices of one group are framed together; empty: none
};

// `hmi: shapes:` — static drawing: rect (x, y, w, h), circle (x, y, r), line (x, y to x2, y2),
// text (label at x, y). Every kind may carry a `label` and a `colour`.
struct HmiShape {
  enum class Kind { Rect, Circle, Line, Text };
  Kind kind = Kind::Rect;
  double x = 0, y = 0, w = 0, h = 0, r = 0, x2 = 0, y2 = 0;
  std::string label;
  std::string colour;  // checked: #rgb, #rrggbb or a CSS colour name; empty: the page's default
};

struct HmiSettings {
  std::vector<DevicePlacement> devices;  // in file order
  std::vector<HmiShape> shapes;          // drawn in file order, under the devices
};

const char* shapeKindName(HmiShape::Kind kind);

}  // namespace virtcom::cell
