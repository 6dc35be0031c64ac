// The external writes in the HTML report (report/html_writes.hpp): the panel with its table
// (golden file), escaping, the empty state, the note of writes beyond those kept, no panel when
// the writes were not audited, and the panel in the run report.
#include <gtest/gtest.h>

#include "report/html_report.hpp"
#include "report/html_writes.hpp"
#include "report/kpis.hpp"
#include "example_trace.hpp"
#include "golden_file.hpp"

namespace virtcom::report {
namespace {

constexpr int64_t kWall = 1'796'313'601'123'000'000;  // 2026-12-03T16:00:01.123Z

// Three writes as the audit records them, into a trace: a Modbus register of a located variable,
// an ADS write of a struct member (with the AmsNetId) and an HMI force of a string with markup.
void keepThreeWrites(Trace& t) {
  t.writesAudited = true;
  t.keepExternalWrite({120'000'000, kWall, {WriteProtocol::Modbus, 0x7F000001, 50123}, "MAIN.setpoint", "%MW0", "0", "21"});
  ExternalWriter ads{WriteProtocol::Ads, 0x7F000001, 40211};
  ads.hasNetId = true;
  ads.netId = {127, 0, 0, 1, 1, 1};
  t.keepExternalWrite({2'410'000'000, kWall + 2'290'000'000, ads, "MAIN.point.y", "", "0.0", "2.5"});
  ExternalWriter page{WriteProtocol::Http, 0x7F000001, 38812};
  page.force = true;
  t.keepExternalWrite({4'200'000'000, kWall + 4'087'000'000, page, "MAIN.name", "", "''", "'<b>'"});
}

Trace auditedTrace() {
  Trace t;
  keepThreeWrites(t);
  return t;
}

TEST(ExternalWritesHtml, PanelMatchesGolden) {
  testing::expectGolden("external_writes.html", externalWritesHtml(auditedTrace()));
}

TEST(ExternalWritesHtml, ValuesAreEscaped) {
  std::string html = externalWritesHtml(auditedTrace());
  EXPECT_NE(html.find("&#39;&#39; \u2192 &#39;&lt;b&gt;&#39; (forced)</td>"), std::string::npos) << html;
  EXPECT_EQ(html.find("<b>"), std::string::npos) << html;
}

TEST(ExternalWritesHtml, ARunWithoutWritesSaysSo) {
  Trace t;
  t.writesAudited = true;
  std::string html = externalWritesHtml(t);
  EXPECT_NE(html.find("<h2>0 external writes (ads 0, modbus 0, opcua 0, http 0)<span"), std::string::npos) << html;
  EXPECT_NE(html.find("<p class=\"note\">No client wrote into the PLC during this run.</p>"), std::string::npos) << html;
  EXPECT_EQ(html.find("<table"), std::string::npos) << html;
}

TEST(ExternalWritesHtml, UnauditedRunsHaveNoPanel) { EXPECT_EQ(externalWritesHtml(Trace{}), ""); }

// A client writing every scan: the trace keeps the first records and counts them all; the
// report lists those kept and says how many it leaves out.
TEST(ExternalWritesHtml, AHugeRunListsTheFirstWritesOnly) {
  Trace t;
  t.writesAudited = true;
  const WriteRecord each{0, kWall, {WriteProtocol::Modbus, 0x7F000001, 50123}, "MAIN.setpoint", "%MW0", "0", "1"};
  for (size_t i = 0; i < Trace::kKeptWriteRecords + 234; ++i) t.keepExternalWrite(each);
  EXPECT_EQ(t.writeRecords.size(), Trace::kKeptWriteRecords);
  EXPECT_EQ(t.externalWrites[static_cast<size_t>(WriteProtocol::Modbus)], Trace::kKeptWriteRecords + 234);
  std::string html = externalWritesHtml(t);
  EXPECT_NE(html.find("<h2>1234 external writes (ads 0, modbus 1234, opcua 0, http 0)<span"), std::string::npos);
  EXPECT_NE(html.find("<p class=\"note\">234 more not shown: the report lists the first 1000.</p>"), std::string::npos);
  size_t rows = 0;
  for (size_t at = html.find("<tr><td>"); at != std::string::npos; at = html.find("<tr><td>", at + 1)) ++rows;
  EXPECT_EQ(rows, Trace::kKeptWriteRecords);
  EXPECT_EQ(externalWritesHtml(auditedTrace()).find("more not shown"), std::string::npos);
}

TEST(ExternalWritesHtml, RunReportShowsThePanelWhenAudited) {
  Trace t = testing::exampleCellTrace();
  EXPECT_EQ(htmlReport(t, computeKpis(t), {}).find("id=\"writes\""), std::string::npos);
  keepThreeWrites(t);
  EXPECT_NE(htmlReport(t, computeKpis(t), {}).find(externalWritesHtml(t)), std::string::npos);
}

}  // namespace
}  // namespace virtcom::report
