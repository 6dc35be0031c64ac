#include "core/coverage.hpp"

#include <algorithm>
#include <tuple>

namespace virtcom {

namespace {

auto key(const CoveragePoint& p) {
  return std::tie(p.file, p.line, p.column, p.kind, p.arm, p.name, p.pou, p.arms);
}

bool before(const CoveragePoint& a, const CoveragePoint& b) { return key(a) < key(b); }

}  // namespace

const char* coverageKindName(CoverageKind k) {
  switch (k) {
    case CoverageKind::Statement: return "statement";
    case CoverageKind::Branch: return "branch";
    case CoverageKind::Step: return "step";
    case CoverageKind::Transition: return "transition";
    case CoverageKind::Rule: return "rule";
  }
  return "?";
}

bool sameCoveragePoint(const CoveragePoint& a, const CoveragePoint& b) { return key(a) == key(b); }

CoverageData::CoverageData(std::vector<CoveragePoint> points) : points_(std::move(points)) {
  std::stable_sort(points_.begin(), points_.end(), before);
  // Two probes at one place (a statement the compiler emits twice) count as one point.
  std::vector<CoveragePoint> unique;
  for (CoveragePoint& p : points_) {
    if (!unique.empty() && sameCoveragePoint(unique.back(), p)) unique.back().count += p.count;
    else unique.push_back(std::move(p));
  }
  points_ = std::move(unique);
}

void CoverageData::merge(const CoverageData& other) {
  std::vector<CoveragePoint> out;
  out.reserve(points_.size() + other.points_.size());
  auto a = points_.begin();
  auto b = other.points_.begin();
  while (a != points_.end() || b != other.points_.end()) {
    if (b == other.points_.end() || (a != points_.end() && before(*a, *b))) {
      out.push_back(std::move(*a++));
    } else if (a == points_.end() || before(*b, *a)) {
      out.push_back(*b++);
    } else {
      out.push_back(std::move(*a++));
      out.back().count += (b++)->count;
    }
  }
  points_ = std::move(out);
}

}  // namespace virtcom
