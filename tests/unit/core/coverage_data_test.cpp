// CoverageData: points kept sorted, merged by adding counts, in any order.
#include <gtest/gtest.h>

#include "core/coverage.hpp"

using namespace virtcom;

namespace {

CoveragePoint point(std::string file, uint32_t line, uint64_t count, CoverageKind kind = CoverageKind::Statement,
                    uint32_t arm = 0) {
  CoveragePoint p;
  p.file = std::move(file);
  p.pou = "MAIN";
  p.line = line;
  p.column = 1;
  p.kind = kind;
  p.arm = arm;
  p.arms = kind == CoverageKind::Branch ? 2 : 0;
  p.count = count;
  return p;
}

TEST(CoverageData, PointsAreSortedAndOnePlaceCountsOnce) {
  CoverageData d({point("b.st", 1, 1), point("a.st", 7, 2), point("a.st", 3, 5), point("a.st", 3, 1)});
  ASSERT_EQ(d.points().size(), 3u);
  EXPECT_EQ(d.points()[0].file, "a.st");
  EXPECT_EQ(d.points()[0].line, 3u);
  EXPECT_EQ(d.points()[0].count, 6u);
  EXPECT_EQ(d.points()[2].file, "b.st");
}

TEST(CoverageData, MergeAddsCountsOfTheSamePointAndKeepsTheOthers) {
  CoverageData a({point("a.st", 3, 1), point("a.st", 4, 0, CoverageKind::Branch, 0), point("a.st", 4, 2, CoverageKind::Branch, 1)});
  CoverageData b({point("a.st", 3, 10), point("a.st", 4, 5, CoverageKind::Branch, 0), point("c.st", 1, 7)});
  CoverageData ab = a, ba = b;
  ab.merge(b);
  ba.merge(a);
  ASSERT_EQ(ab.points().size(), 4u);
  EXPECT_EQ(ab.points()[0].count, 11u);  // a.st:3
  EXPECT_EQ(ab.points()[1].count, 5u);   // a.st:4 arm 0
  EXPECT_EQ(ab.points()[2].count, 2u);   // a.st:4 arm 1, only in a
  EXPECT_EQ(ab.points()[3].file, "c.st");
  ASSERT_EQ(ba.points().size(), ab.points().size());
  for (size_t i = 0; i < ab.points().size(); ++i) {
    EXPECT_TRUE(sameCoveragePoint(ab.points()[i], ba.points()[i]));
    EXPECT_EQ(ab.points()[i].count, ba.points()[i].count);
  }
}

TEST(CoverageData, MergingIntoEmptyCopies) {
  CoverageData empty;
  empty.merge(CoverageData({point("a.st", 1, 3)}));
  ASSERT_EQ(empty.points().size(), 1u);
  EXPECT_EQ(empty.points()[0].count, 3u);
  EXPECT_STREQ(coverageKindName(CoverageKind::Transition), "transition");
  EXPECT_STREQ(coverageKindName(CoverageKind::Rule), "rule");
}

}  // namespace
