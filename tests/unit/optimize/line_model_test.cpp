// The benchmark line of bench/optimise/ (docs/scaling.md): it loads, its hand-written sequences
// run to a completed cycle, and it is the larger model it is there to be (the gearbox has 24
// distinct candidates; counting the line's up to the exhaustive limit takes too long for a test).
#include <gtest/gtest.h>

#include "optimize/evaluator.hpp"
#include "optimize/search.hpp"

namespace virtcom::optimize {
namespace {

TEST(LineModel, LoadsRunsItsSequencesAndHasOverAThousandDistinctCandidates) {
  SourceManager sources;
  Diagnostics diags;
  auto model = readProcessModel(VIRTCOM_SOURCE_DIR "/bench/optimise/line_model.yaml", sources, diags);
  ASSERT_TRUE(model) << diags.render(sources);
  auto evaluator = Evaluator::create(*model, sources, diags);
  ASSERT_TRUE(evaluator) << diags.render(sources);
  EXPECT_FALSE(diags.hasErrors());
  ASSERT_EQ(model->sequences.size(), 2u);
  for (const auto& s : model->sequences) {
    const Evaluation e = evaluator->evaluate(buildJobList(*model, s.candidate));
    EXPECT_TRUE(e.feasible) << s.name << ": " << e.reason;
    EXPECT_GT(e.cycleNs, 0) << s.name;
  }
  EXPECT_GT(enumerateCandidates(*model, 1000).size(), 1000u);
}

}  // namespace
}  // namespace virtcom::optimize
