// Ranks without mpirun: one rank, the leader, every evaluation done here in index order (the
// MPI case, two ranks giving the single-process result, is tests/e2e/optimise_e2e_test.cpp).
#include <gtest/gtest.h>

#include "optimize/ranks.hpp"

namespace virtcom::optimize {
namespace {

TEST(Ranks, WithoutMpirunOneRankEvaluatesEveryIndexInOrder) {
  const Ranks ranks;
  EXPECT_EQ(ranks.size(), 1);
  EXPECT_TRUE(ranks.leader());
  const std::vector<Evaluation> all = ranks.evaluateAll(37, 3, [](size_t i) {
    Evaluation e;
    e.feasible = i % 5 != 0;
    e.cycleNs = static_cast<int64_t>(i) * 1000;
    e.reason = e.feasible ? "" : "deadlock " + std::to_string(i);
    return e;
  });
  ASSERT_EQ(all.size(), 37u);
  for (size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(all[i].cycleNs, static_cast<int64_t>(i) * 1000);
    EXPECT_EQ(all[i].feasible, i % 5 != 0);
  }
  EXPECT_EQ(all[35].reason, "deadlock 35");
  EXPECT_TRUE(ranks.leaderDecides(true));
  EXPECT_FALSE(ranks.leaderDecides(false));
}

}  // namespace
}  // namespace virtcom::optimize
