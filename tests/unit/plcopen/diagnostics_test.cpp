// Every tests/golden/plcopen/errors/*.xml is compiled; its rendered diagnostics (file:line:col of
// the XML element, code, message naming the element and its localId) must equal the .diag file
// next to it. VIRTCOM_UPDATE_GOLDEN=1 rewrites the .diag files for review.
#include <algorithm>

#include "plcopen_fixture.hpp"

namespace virtcom::plcopen::testing {
namespace {

std::vector<std::string> errorCases() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(kGoldenDir / "errors"))
    if (entry.path().extension() == ".xml") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

class PlcopenDiagnostics : public ::testing::TestWithParam<std::string> {};

TEST_P(PlcopenDiagnostics, MatchGolden) {
  std::string rel = "errors/" + GetParam() + ".xml";
  auto c = compile({input(rel, readFile(kGoldenDir / rel))});
  EXPECT_EQ(c->module, nullptr) << "expected errors";
  std::string rendered = c->rendered();
  auto diagFile = kGoldenDir / "errors" / (GetParam() + ".diag");
  if (std::getenv("VIRTCOM_UPDATE_GOLDEN")) {
    std::ofstream(diagFile, std::ios::binary) << rendered;
    return;
  }
  ASSERT_TRUE(std::filesystem::exists(diagFile)) << "missing " << diagFile << "; run with VIRTCOM_UPDATE_GOLDEN=1 and review it";
  EXPECT_EQ(readFile(diagFile), rendered);
}

INSTANTIATE_TEST_SUITE_P(Errors, PlcopenDiagnostics, ::testing::ValuesIn(errorCases()));

TEST(PlcopenLocations, StBodyErrorsPointIntoTheXml) {
  std::string xml =
      "<project xmlns=\"http://www.plcopen.org/xml/tc6_0201\"><types><pous>\n"
      "<pou name=\"P\" pouType=\"program\"><body><ST><p><![CDATA[x := 1;\n"
      "  y := ;]]></p></ST></body></pou></pous></types></project>";
  auto c = compile({input("p.xml", xml)});
  ASSERT_FALSE(c->diags.all().empty());
  const Diagnostic& d = c->diags.all().front();
  EXPECT_EQ(d.loc.line, 3u);
  EXPECT_EQ(d.loc.col, 8u) << c->rendered();
}

}  // namespace
}  // namespace virtcom::plcopen::testing
