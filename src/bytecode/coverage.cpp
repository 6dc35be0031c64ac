#include "bytecode/coverage.hpp"

#include <cstring>

namespace virtcom::bc {

CoverageData collectCoverage(const Module& m, const uint8_t* memory) {
  std::vector<CoveragePoint> points;
  points.reserve(m.coverage.probes.size());
  for (size_t i = 0; i < m.coverage.probes.size(); ++i) {
    const CoverageProbe& probe = m.coverage.probes[i];
    CoveragePoint p;
    p.file = probe.loc.fileId < m.files.size() ? m.files[probe.loc.fileId] : std::string();
    p.pou = probe.pou < m.pous.size() ? m.pous[probe.pou].name : std::string();
    p.line = probe.loc.line;
    p.column = probe.loc.col;
    p.kind = probe.kind;
    p.arm = probe.arm;
    p.arms = probe.arms;
    p.name = probe.name;
    // Counters are little-endian u64 like every value of the image (the VM's loadLe).
    uint8_t bytes[8];
    std::memcpy(bytes, memory + m.coverage.counterAddress + 8 * i, 8);
    for (int b = 7; b >= 0; --b) p.count = p.count << 8 | bytes[b];
    points.push_back(std::move(p));
  }
  return CoverageData(std::move(points));
}

}  // namespace virtcom::bc
