// Diagnostics as the user sees them: `file:line:col: error[CODE]: message`, the quoted source
// line, a caret under the column, and a summary line. Compared as whole strings on purpose.
#include <gtest/gtest.h>

#include "core/diagnostics.hpp"
#include "core/source.hpp"

namespace virtcom {
namespace {

TEST(Diagnostics, RendersLocationCodeSourceLineAndCaret) {
  SourceManager sources;
  uint32_t f = sources.addFile("main.st", "PROGRAM MAIN\n  x := 1 / ;\nEND_PROGRAM\n");
  Diagnostics diags;
  diags.error("E006", {f, 2, 12}, "unexpected token ';'");
  EXPECT_EQ(diags.render(sources),
            "main.st:2:12: error[E006]: unexpected token ';'\n"
            "    x := 1 / ;\n"
            "             ^\n"
            "1 error(s), 0 warning(s)\n");
}

TEST(Diagnostics, CaretInColumnOneHasNoPadding) {
  SourceManager sources;
  uint32_t f = sources.addFile("a.st", "FOO\n");
  Diagnostic d{Severity::Error, "E201", {f, 1, 1}, "undeclared name 'FOO'"};
  EXPECT_EQ(renderDiagnostic(d, sources),
            "a.st:1:1: error[E201]: undeclared name 'FOO'\n"
            "  FOO\n"
            "  ^\n");
}

TEST(Diagnostics, TabsBeforeTheColumnAreKeptSoTheCaretLinesUp) {
  SourceManager sources;
  uint32_t f = sources.addFile("t.st", "\t\tx := y;\n");
  Diagnostic d{Severity::Error, "E201", {f, 1, 8}, "undeclared name 'y'"};
  EXPECT_EQ(renderDiagnostic(d, sources),
            "t.st:1:8: error[E201]: undeclared name 'y'\n"
            "  \t\tx := y;\n"
            "  \t\t     ^\n");
}

TEST(Diagnostics, ColumnPastTheEndPutsTheCaretJustAfterTheLastCharacter) {
  SourceManager sources;
  uint32_t f = sources.addFile("a.st", "abc\n");
  Diagnostic d{Severity::Error, "E007", {f, 1, 40}, "missing END_IF"};
  EXPECT_EQ(renderDiagnostic(d, sources),
            "a.st:1:40: error[E007]: missing END_IF\n"
            "  abc\n"
            "     ^\n");
}

TEST(Diagnostics, CrLfSourceQuotesTheLineWithoutTheCarriageReturn) {
  SourceManager sources;
  uint32_t f = sources.addFile("w.st", "a := 1;\r\nb := ;\r\n");
  Diagnostic d{Severity::Error, "E006", {f, 2, 6}, "unexpected token"};
  EXPECT_EQ(renderDiagnostic(d, sources),
            "w.st:2:6: error[E006]: unexpected token\n"
            "  b := ;\n"
            "       ^\n");
}

TEST(Diagnostics, WarningAndNoteSeverities) {
  SourceManager sources;
  uint32_t f = sources.addFile("a.st", "x\n");
  EXPECT_EQ(renderDiagnostic({Severity::Warning, "W001", {f, 1, 1}, "unused"}, sources),
            "a.st:1:1: warning[W001]: unused\n  x\n  ^\n");
  EXPECT_EQ(renderDiagnostic({Severity::Note, "", {f, 1, 1}, "declared here"}, sources),
            "a.st:1:1: note: declared here\n  x\n  ^\n");
}

TEST(Diagnostics, EmptyLineIsNotQuoted) {
  SourceManager sources;
  uint32_t f = sources.addFile("a.st", "x\n\ny\n");
  EXPECT_EQ(renderDiagnostic({Severity::Error, "E006", {f, 2, 1}, "m"}, sources), "a.st:2:1: error[E006]: m\n");
}

TEST(Diagnostics, LineZeroMeansNoPositionInTheFile) {
  SourceManager sources;
  uint32_t f = sources.addFile("a.st", "x\n");
  EXPECT_EQ(renderDiagnostic({Severity::Error, "E217", {f, 0, 0}, "no PROGRAM"}, sources),
            "a.st: error[E217]: no PROGRAM\n");
}

TEST(Diagnostics, UnknownFileRendersOnlySeverityCodeAndMessage) {
  SourceManager sources;
  EXPECT_EQ(renderDiagnostic({Severity::Error, "E999", {7, 3, 4}, "internal"}, sources), "error[E999]: internal\n");
}

TEST(Diagnostics, SummaryCountsErrorsAndWarningsButNotNotes) {
  SourceManager sources;
  uint32_t f = sources.addFile("a.st", "x\n");
  Diagnostics diags;
  diags.error("E1", {f, 1, 1}, "e1");
  diags.warning("W1", {f, 1, 1}, "w1");
  diags.report(Severity::Note, "", {f, 1, 1}, "n1");
  diags.error("E2", {f, 1, 1}, "e2");
  EXPECT_EQ(diags.errorCount(), 2u);
  EXPECT_EQ(diags.warningCount(), 1u);
  EXPECT_TRUE(diags.hasErrors());
  std::string out = diags.render(sources);
  EXPECT_TRUE(out.ends_with("\n2 error(s), 1 warning(s)\n")) << out;
}

TEST(Diagnostics, WarningsOnlyDoNotCountAsErrors) {
  SourceManager sources;
  uint32_t f = sources.addFile("a.st", "x\n");
  Diagnostics diags;
  diags.warning("W1", {f, 1, 1}, "w");
  EXPECT_FALSE(diags.hasErrors());
  EXPECT_TRUE(diags.render(sources).ends_with("0 error(s), 1 warning(s)\n"));
}

TEST(Diagnostics, NothingReportedRendersNothing) {
  SourceManager sources;
  Diagnostics diags;
  EXPECT_EQ(diags.render(sources), "");
  EXPECT_FALSE(diags.hasErrors());
}

TEST(Diagnostics, SortByLocationOrdersByFileLineColumnAndIsStable) {
  SourceManager sources;
  uint32_t a = sources.addFile("a.st", "1\n2\n3\n");
  uint32_t b = sources.addFile("b.st", "1\n");
  Diagnostics diags;
  diags.error("E", {b, 1, 1}, "b1");
  diags.error("E", {a, 3, 1}, "a3");
  diags.error("E", {a, 2, 9}, "a2c9");
  diags.error("E", {a, 2, 2}, "a2c2-first");
  diags.warning("W", {a, 2, 2}, "a2c2-second");
  diags.error("E", {a, 2, 2}, "a2c2-third");
  diags.sortByLocation();
  std::vector<std::string> order;
  for (const auto& d : diags.all()) order.push_back(d.message);
  EXPECT_EQ(order, (std::vector<std::string>{"a2c2-first", "a2c2-second", "a2c2-third", "a2c9", "a3", "b1"}));
}

TEST(Diagnostics, RenderAfterSortIsInLocationOrder) {
  SourceManager sources;
  uint32_t f = sources.addFile("a.st", "aa\nbb\n");
  Diagnostics diags;
  diags.error("E2", {f, 2, 1}, "second line");
  diags.error("E1", {f, 1, 2}, "first line");
  diags.sortByLocation();
  EXPECT_EQ(diags.render(sources),
            "a.st:1:2: error[E1]: first line\n"
            "  aa\n"
            "   ^\n"
            "a.st:2:1: error[E2]: second line\n"
            "  bb\n"
            "  ^\n"
            "2 error(s), 0 warning(s)\n");
}

}  // namespace
}  // namespace virtcom
