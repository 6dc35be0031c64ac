#pragma once
// A generated cell of N identical stations, for measuring how the simulation's cost grows with
// the cell (issue 21): each station is a belt bringing parts, a part sensor, a robot carrying
// each part into a press, and the press; one FB_Station instance per station runs its handshakes.
// 4 devices per station; the run is endless (ended by the time limit), parts keep coming.
#include <cstdint>
#include <string>

namespace virtcom::bench {

struct ScalingCellFiles {
  std::string yaml;  // the cell file; its PLC source is `scaling_cell.st` next to it
  std::string st;
};

ScalingCellFiles scalingCell(int stations, int64_t taskNs);
// Writes DIR/scaling_cell.yaml and DIR/scaling_cell.st (creating DIR); returns the cell file's
// path, or an empty string with `error` set.
std::string writeScalingCell(const std::string& dir, int stations, int64_t taskNs, std::string& error);

constexpr int kDevicesPerStation = 4;

}  // namespace virtcom::bench
