// The tag bus's change bookkeeping at its edges.
#include <gtest/gtest.h>

#include "core/tag_bus.hpp"

namespace virtcom {
namespace {

// Regression: a cell without devices has an empty bus, whose clearChanges() once passed a
// null pointer to memset (undefined behaviour; UBSan stopped the run).
TEST(TagBus, EmptyBusClearsAndVisitsNoChanges) {
  TagBus bus;
  bus.clearChanges();
  int visited = 0;
  bus.forEachChanged([&](TagId) { ++visited; });
  EXPECT_EQ(visited, 0);
}

TEST(TagBus, ClearChangesForgetsEveryChangedTag) {
  TagBus bus;
  TagId a = bus.add("a", ElemType::Lint);
  TagId b = bus.add("b", ElemType::Bool);
  bus.setInt(a, 7);
  bus.setBool(b, true);
  int visited = 0;
  bus.forEachChanged([&](TagId) { ++visited; });
  EXPECT_EQ(visited, 2);
  bus.clearChanges();
  visited = 0;
  bus.forEachChanged([&](TagId) { ++visited; });
  EXPECT_EQ(visited, 0);
}

}  // namespace
}  // namespace virtcom
