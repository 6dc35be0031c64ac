// The process model file: what it reads, the mistakes it reports (C070 at file:line:col), and
// the job lists derived from its candidates.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "optimize/job_list.hpp"
#include "optimize/process_model.hpp"

namespace virtcom::optimize {
namespace {

const std::string kData = VIRTCOM_SOURCE_DIR "/tests/unit/optimize/data/";
const std::string kGearbox = VIRTCOM_SOURCE_DIR "/examples/gearbox-cell/process.yaml";

struct Read {
  SourceManager sources;
  Diagnostics diags;
  std::optional<ProcessModel> model;
  std::string text;
};

std::unique_ptr<Read> readFile(const std::string& path) {
  auto r = std::make_unique<Read>();
  r->model = readProcessModel(path, r->sources, r->diags);
  r->text = r->diags.render(r->sources);
  return r;
}

// A variant of the two-robot model with `from` replaced by `to`, written next to the original.
std::unique_ptr<Read> readVariant(const std::string& from, const std::string& to) {
  std::ifstream in(kData + "two_robots_model.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  const std::string path = (std::filesystem::temp_directory_path() / ("optimize_model_" + std::to_string(::getpid()) + ".yaml")).string();
  std::ofstream(path) << text;
  auto r = readFile(path);
  std::filesystem::remove(path);
  return r;
}

TEST(ProcessModel, ReadsOperationsAlternativesPrecedenceAndSequences) {
  auto r = readFile(kData + "two_robots_model.yaml");
  ASSERT_TRUE(r->model) << r->text;
  const ProcessModel& m = *r->model;
  ASSERT_EQ(m.operations.size(), 6u);
  EXPECT_EQ(m.operations[4].alternatives.size(), 2u);
  EXPECT_EQ(m.operations[4].alternatives[1].name, "OnR2");
  EXPECT_EQ(m.operations[4].alternatives[1].device, 2);
  EXPECT_TRUE(m.operations[5].optional);
  EXPECT_TRUE(m.precedes[0][2]);   // A before C
  EXPECT_FALSE(m.precedes[2][0]);
  EXPECT_TRUE(m.precedes[3][4]);   // D before E
  ASSERT_EQ(m.sequences.size(), 2u);
  EXPECT_EQ(m.sequences[1].candidate.choice[5], kSkipped);
  EXPECT_TRUE(m.sequences[1].candidate.ignoreResources);
  EXPECT_EQ(m.jobList.count, "MAIN.jobCount");
  EXPECT_EQ(std::filesystem::path(m.cellFile).filename(), "two_robots.yaml");
}

TEST(ProcessModel, UnknownOperationInAfterIsReportedWhereItIsWritten) {
  auto r = readVariant("after: [A] }", "after: [Z] }");
  EXPECT_FALSE(r->model);
  EXPECT_NE(r->text.find(".yaml:13:45: error[C070]: 'after' of 'C' names 'Z', which is no operation of the model"), std::string::npos) << r->text;
}

TEST(ProcessModel, CyclicPrecedenceIsRefused) {
  auto r = readVariant("{ name: A, device: R1, code: 2 }", "{ name: A, device: R1, code: 2, after: [C] }");
  EXPECT_FALSE(r->model);
  EXPECT_NE(r->text.find("must finish before itself"), std::string::npos) << r->text;
}

TEST(ProcessModel, SequenceOutOfPrecedenceOrMissingAMandatoryOperationIsRefused) {
  auto r = readVariant("order: [A, B, C, D, E, F]", "order: [C, A, B, D]");
  EXPECT_FALSE(r->model);
  EXPECT_NE(r->text.find("error[C070]: sequence 'listed' lists 'A' after 'C', which must come after it"), std::string::npos) << r->text;
  EXPECT_NE(r->text.find("sequence 'listed' leaves out 'E', which is not optional"), std::string::npos) << r->text;
}

TEST(ProcessModel, UnknownDeviceAndAlternativeAreReportedWithWhatExists) {
  auto r = readVariant("{ name: D, device: R2, code: 2 }", "{ name: D, device: R3, code: 2 }");
  EXPECT_NE(r->text.find("no device 'R3' in the model's 'device_numbers' (expected one of: R1, R2)"), std::string::npos) << r->text;
  auto c = readVariant("order: [A, B, C, D, E, F] }", "order: [A, B, C, D, E, F], choose: { E: OnR3 } }");
  EXPECT_NE(c->text.find("operation 'E' has no alternative 'OnR3' (expected one of: OnR1, OnR2)"), std::string::npos) << c->text;
}

TEST(ProcessModel, TyposInKeysAreUnknownKeys) {
  auto r = readVariant("time_limit: 30 s", "time_limt: 30 s");
  EXPECT_NE(r->text.find("error[C011]: unknown key 'time_limt'"), std::string::npos) << r->text;
}

TEST(JobList, WaitsAreTheFewestThatKeepPrecedenceAndResources) {
  auto r = readFile(kData + "two_robots_model.yaml");
  ASSERT_TRUE(r->model) << r->text;
  const ProcessModel& m = *r->model;
  JobList list = buildJobList(m, m.sequences[0].candidate);
  ASSERT_EQ(list.jobs.size(), 6u);
  // A(R1) B(R1, table) C(R2, table, after A) D(R2) E(R1) F(R2)
  EXPECT_TRUE(list.jobs[1].waits.empty()) << "B follows A on its own device";
  EXPECT_EQ(list.jobs[2].waits, std::vector<uint32_t>{2}) << "C waits for B (the table), which implies A";
  EXPECT_EQ(list.jobs[4].waits, std::vector<uint32_t>{4}) << "E waits for D";
  JobList loose = buildJobList(m, m.sequences[1].candidate);
  EXPECT_EQ(loose.jobs[2].waits, std::vector<uint32_t>{1}) << "without the resource, C waits only for A";
  EXPECT_NE(list.key, loose.key);
}

TEST(JobList, OrdersThatTheProgramRunsAlikeShareTheirKey) {
  auto r = readFile(kData + "two_robots_model.yaml");
  ASSERT_TRUE(r->model);
  const ProcessModel& m = *r->model;
  Candidate a = m.sequences[0].candidate;
  Candidate b = a;
  b.order = {0, 1, 2, 3, 5, 4};  // F (R2) before E (R1): other devices, no constraint between them
  ASSERT_EQ(checkCandidate(m, b), "");
  EXPECT_EQ(buildJobList(m, a).key, buildJobList(m, b).key);
  Candidate c = a;
  c.choice[4] = 1;  // E on R2
  EXPECT_NE(buildJobList(m, a).key, buildJobList(m, c).key);
}

TEST(JobList, CheckCandidateNamesTheBrokenPrecedence) {
  auto r = readFile(kData + "two_robots_model.yaml");
  ASSERT_TRUE(r->model);
  Candidate c = r->model->sequences[0].candidate;
  c.order = {2, 0, 1, 3, 4, 5};
  EXPECT_EQ(checkCandidate(*r->model, c), "'A' comes before 'C' but must follow it");
}

TEST(JobList, StTextIsAnInitialiserWithOneCommentedJobPerLine) {
  auto r = readFile(kData + "two_robots_model.yaml");
  ASSERT_TRUE(r->model);
  const ProcessModel& m = *r->model;
  const std::string st = jobListSt(m, buildJobList(m, m.sequences[0].candidate), "jobs", "ARRAY [1..8] OF ST_Job");
  EXPECT_EQ(st.substr(0, st.find('\n')), "jobs : ARRAY [1..8] OF ST_Job := [");
  EXPECT_NE(st.find("(device := 2, code := 3, after1 := 2),"), std::string::npos) << st;
  EXPECT_NE(st.find("(* 3 C on R2 *)"), std::string::npos) << st;
  EXPECT_NE(st.find("];"), std::string::npos);
}

TEST(ProcessModel, GearboxModelReadsWithItsFourSequences) {
  auto r = readFile(kGearbox);
  ASSERT_TRUE(r->model) << r->text;
  ASSERT_EQ(r->model->sequences.size(), 4u);
  for (const auto& s : r->model->sequences) EXPECT_EQ(checkCandidate(*r->model, s.candidate), "") << s.name;
}

}  // namespace
}  // namespace virtcom::optimize
