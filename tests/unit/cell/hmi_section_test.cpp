// The cell file's `hmi:` section (docs/cell-file.md, docs/hmi.md): placements and static shapes
// read into Cell::hmi, and every mistake at its position (C010, C011, C040, C041).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cell_files.hpp"

namespace virtcom::cell::test {
namespace {

using ::testing::ElementsAre;

// No PLC: the section needs only devices. Line 15 is the first line after it.
constexpr const char* kDevices = R"(devices:
  - name: Clamp
    type: timed
    commands:
      1: { name: Close, duration: 1 s }
  - name: Robot
    type: robot
    max_speed: 500 mm/s
    acceleration: 1 m/s^2
    locations:
      Home: "0, 0, 0 mm"
      Pick: "100, 0, 0 mm"
    procedures:
      1: { name: P1, steps: [move Pick] }
)";

using HmiSection = CellFiles;

TEST_F(HmiSection, PlacementsAndShapesAreReadInMetres) {
  auto cell = loads(std::string(kDevices) +
                    "hmi:\n"
                    "  devices:\n"
                    "    Clamp: { x: 1200 mm, y: -0.5 m, w: 600 mm, h: 400 mm, label: Clamping unit, group: Station 1 }\n"
                    "    Robot: { base: \"2000, 100 mm\" }\n"
                    "  shapes:\n"
                    "    - { kind: rect, x: 0 mm, y: 0 mm, w: 3 m, h: 2 m, label: fence, colour: \"#abc\" }\n"
                    "    - { kind: circle, x: 1 m, y: 1 m, r: 100 mm, colour: steelblue }\n"
                    "    - { kind: line, x: 0 mm, y: 0 mm, x2: 1 m, y2: 0 mm }\n"
                    "    - { kind: text, x: 0 mm, y: -200 mm, label: operator side }\n");
  ASSERT_TRUE(cell);
  const HmiSettings& hmi = cell->hmi;
  ASSERT_EQ(hmi.devices.size(), 2u);
  EXPECT_EQ(hmi.devices[0].device, 0u);
  EXPECT_DOUBLE_EQ(*hmi.devices[0].x, 1.2);
  EXPECT_DOUBLE_EQ(*hmi.devices[0].y, -0.5);
  EXPECT_DOUBLE_EQ(*hmi.devices[0].w, 0.6);
  EXPECT_DOUBLE_EQ(*hmi.devices[0].h, 0.4);
  EXPECT_EQ(hmi.devices[0].label, "Clamping unit");
  EXPECT_EQ(hmi.devices[0].group, "Station 1");
  EXPECT_FALSE(hmi.devices[0].baseX);
  EXPECT_EQ(hmi.devices[1].device, 1u);
  EXPECT_DOUBLE_EQ(*hmi.devices[1].baseX, 2.0);
  EXPECT_DOUBLE_EQ(*hmi.devices[1].baseY, 0.1);
  EXPECT_FALSE(hmi.devices[1].x);
  ASSERT_EQ(hmi.shapes.size(), 4u);
  EXPECT_EQ(hmi.shapes[0].kind, HmiShape::Kind::Rect);
  EXPECT_DOUBLE_EQ(hmi.shapes[0].w, 3.0);
  EXPECT_EQ(hmi.shapes[0].colour, "#abc");
  EXPECT_EQ(hmi.shapes[1].kind, HmiShape::Kind::Circle);
  EXPECT_DOUBLE_EQ(hmi.shapes[1].r, 0.1);
  EXPECT_EQ(hmi.shapes[2].kind, HmiShape::Kind::Line);
  EXPECT_DOUBLE_EQ(hmi.shapes[2].x2, 1.0);
  EXPECT_EQ(hmi.shapes[3].kind, HmiShape::Kind::Text);
  EXPECT_EQ(hmi.shapes[3].label, "operator side");
}

TEST_F(HmiSection, WithoutTheSectionNothingIsPlaced) {
  auto cell = loads(kDevices);
  ASSERT_TRUE(cell);
  EXPECT_TRUE(cell->hmi.devices.empty());
  EXPECT_TRUE(cell->hmi.shapes.empty());
}

TEST_F(HmiSection, UnknownKeysAtTheirPosition) {
  EXPECT_THAT(fails(std::string(kDevices) +
                    "hmi:\n"
                    "  devices:\n"
                    "    Clamp: { x: 1 m, y: 1 m, colour: red }\n"
                    "  shapes:\n"
                    "    - { kind: circle, x: 0 mm, y: 0 mm, r: 1 m, width: 2 mm }\n"
                    "  legend: true\n"),
              ElementsAre("cell.yaml:17:30: error[C011]: unknown key 'colour' in 'hmi: devices: Clamp' "
                          "(expected one of: x, y, w, h, label, group, base)",
                          "cell.yaml:19:49: error[C011]: unknown key 'width' in a shape of 'hmi: shapes' "
                          "(expected one of: kind, x, y, r, label, colour)",
                          "cell.yaml:20:3: error[C011]: unknown key 'legend' in 'hmi' (expected one of: devices, shapes)"));
}

TEST_F(HmiSection, UnknownDeviceNameIsC040) {
  EXPECT_THAT(fails(std::string(kDevices) + "hmi:\n  devices:\n    Clmap: { x: 1 m, y: 1 m }\n"),
              ElementsAre("cell.yaml:17:5: error[C040]: 'hmi: devices' names 'Clmap', but the cell has no such device"));
}

TEST_F(HmiSection, BadValuesAreC010) {
  EXPECT_THAT(fails(std::string(kDevices) +
                    "hmi:\n"
                    "  devices:\n"
                    "    Clamp: { x: 1200, y: 2 s, w: -1 m }\n"),
              ElementsAre("cell.yaml:17:17: error[C010]: 'x': '1200' needs a unit: expected a length (e.g. 250 mm)",
                          "cell.yaml:17:26: error[C010]: 'y': '2 s' is not a length (e.g. 250 mm)",
                          "cell.yaml:17:34: error[C010]: 'w' must be positive"));
}

TEST_F(HmiSection, InconsistentDrawingIsC041) {
  EXPECT_THAT(fails(std::string(kDevices) +
                    "hmi:\n"
                    "  devices:\n"
                    "    Clamp: { x: 1 m, base: \"0, 0 mm\" }\n"
                    "  shapes:\n"
                    "    - { kind: star, x: 0 mm, y: 0 mm }\n"
                    "    - { kind: rect, x: 0 mm, y: 0 mm, w: 1 m, h: 1 m, colour: \"red;x\" }\n"),
              ElementsAre("cell.yaml:17:14: error[C041]: 'x' and 'y' go together: 'x' needs 'y'",
                          "cell.yaml:17:28: error[C041]: 'base' places a robot's frame, but 'Clamp' is a timed",
                          "cell.yaml:19:15: error[C041]: unknown shape kind 'star' (expected one of: rect, circle, line, text)",
                          "cell.yaml:20:63: error[C041]: 'colour' must be #rgb, #rrggbb or a CSS colour name such as steelblue, found 'red;x'"));
}

}  // namespace
}  // namespace virtcom::cell::test
