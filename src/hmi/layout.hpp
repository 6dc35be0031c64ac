#pragma once
// Where the layout view draws each device: a top view in cell millimetres (x right, y up),
// generated from the cell file with no drawing work. A robot's box holds its locations (its
// own frame, origin at `originX/Y`); robots stand side by side, every other device gets a box in
// a grid below them. The cell file's `hmi: devices:` places devices itself (a robot by its base,
// any device by its box); the devices it leaves out keep the grid, moved below the placed ones.
#include <vector>

#include "cell/cell.hpp"

namespace virtcom::hmi {

struct Place {
  double x = 0, y = 0, w = 0, h = 0;  // the box, lower-left corner, mm
  double originX = 0, originY = 0;    // robots: where their frame's (0, 0) is, mm
};

// One Place per device of the cell, in device order.
std::vector<Place> placeDevices(const cell::Cell& cell);

}  // namespace virtcom::hmi
