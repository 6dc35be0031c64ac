// make_scaling_cell STATIONS DIR [TASK_MS]: writes the generated scaling cell (scaling_cell.hpp)
// for `virtcom run`, e.g. the memory of a long run: bench/scaling/long_run.sh.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "scaling_cell.hpp"

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4 || std::string(argv[1]) == "--help") {
    std::fprintf(stderr, "usage: make_scaling_cell STATIONS DIR [TASK_MS (default 10)]\n"
                         "writes DIR/scaling_cell.yaml and DIR/scaling_cell.st: STATIONS x (belt, sensor, robot, press)\n");
    return argc == 2 ? 0 : 64;
  }
  int stations = std::atoi(argv[1]);
  double taskMs = argc == 4 ? std::atof(argv[3]) : 10.0;
  if (stations < 1 || taskMs <= 0) {
    std::fprintf(stderr, "make_scaling_cell: STATIONS must be >= 1 and TASK_MS > 0\n");
    return 64;
  }
  std::string error;
  std::string path = virtcom::bench::writeScalingCell(argv[2], stations, static_cast<int64_t>(taskMs * 1e6), error);
  if (path.empty()) {
    std::fprintf(stderr, "make_scaling_cell: %s\n", error.c_str());
    return 1;
  }
  std::printf("%s\n", path.c_str());
  return 0;
}
