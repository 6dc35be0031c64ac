// The ST printer (lang/syntax/printer.hpp) that export relies on: printing a parsed body (or a
// whole POU) and parsing the text again gives the same text, for the ST golden tests.
#include "lang/st/parse/parser.hpp"
#include "lang/syntax/printer.hpp"
#include "plcopen_fixture.hpp"

namespace virtcom::plcopen::testing {
namespace {

void expectFixedPoint(const st::StmtList& body, const std::string& where) {
  std::string once = st::printStatements(body);
  Diagnostics diags;
  st::NodeId next = 0;
  st::StmtList again = st::parseStatements(0, {0, 1, 1}, once, diags, next);
  ASSERT_FALSE(diags.hasErrors()) << where << ":\n" << once;
  EXPECT_EQ(st::printStatements(again), once) << where;
}

void checkPou(const st::Pou& pou, const std::string& file) {
  expectFixedPoint(pou.body, file + " " + pou.name);
  for (const auto& m : pou.methods) checkPou(*m, file);
  for (const auto& a : pou.actions) checkPou(*a, file);
}

TEST(Printer, GoldenStBodiesAreAFixedPoint) {
  auto root = std::filesystem::path(VIRTCOM_SOURCE_DIR) / "tests" / "golden" / "st";
  size_t checked = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    if (entry.path().extension() != ".st" || entry.path().string().find("/errors/") != std::string::npos) continue;
    Diagnostics diags;
    st::NodeId next = 0;
    std::string text = readFile(entry.path());
    st::CompilationUnit unit = st::parseFile(0, text, diags, next);
    if (diags.hasErrors()) continue;
    for (const auto& pou : unit.pous) checkPou(*pou, entry.path().filename().string());
    ++checked;
  }
  EXPECT_GT(checked, 50u);
}

// printPou covers PROGRAMs, FUNCTION_BLOCKs and FUNCTIONs with their VAR blocks and ACTIONs
// (`virtcom ad export --st` prints the lowered diagrams with it).
bool printable(const st::Pou& pou) {
  if (!pou.methods.empty() || !pou.properties.empty() || !pou.extends.empty() || !pou.implements.empty() || pou.chart)
    return false;
  for (const auto& block : pou.varBlocks)
    for (const auto& v : block.vars)
      if (!v.fbInitArgs.empty()) return false;
  return pou.kind == st::PouKind::Program || pou.kind == st::PouKind::FunctionBlock || pou.kind == st::PouKind::Function;
}

TEST(Printer, GoldenStPousAreAFixedPoint) {
  auto root = std::filesystem::path(VIRTCOM_SOURCE_DIR) / "tests" / "golden" / "st";
  size_t checked = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    if (entry.path().extension() != ".st" || entry.path().string().find("/errors/") != std::string::npos) continue;
    Diagnostics diags;
    st::NodeId next = 0;
    st::CompilationUnit unit = st::parseFile(0, readFile(entry.path()), diags, next);
    if (diags.hasErrors()) continue;
    for (const auto& pou : unit.pous) {
      if (!printable(*pou)) continue;
      std::string once = st::printPou(*pou);
      st::CompilationUnit again = st::parseFile(0, once, diags, next);
      ASSERT_FALSE(diags.hasErrors()) << entry.path().filename() << " " << pou->name << ":\n" << once;
      ASSERT_EQ(again.pous.size(), 1u) << once;
      EXPECT_EQ(st::printPou(*again.pous.front()), once) << entry.path().filename();
      ++checked;
    }
  }
  EXPECT_GT(checked, 150u);
}

TEST(Printer, PrecedenceAndLiterals) {
  Diagnostics diags;
  st::NodeId next = 0;
  auto print = [&](const char* text) { return st::printExpr(*st::parseExpression(0, {0, 1, 1}, text, diags, next)); };
  EXPECT_EQ(print("(a + b) * c - (d - e)"), "(a + b) * c - (d - e)");
  EXPECT_EQ(print("a - (b + c)"), "a - (b + c)");
  EXPECT_EQ(print("NOT (a OR b) AND c"), "NOT (a OR b) AND c");
  EXPECT_EQ(print("-(x ** 2)"), "-(x ** 2)");
  EXPECT_EQ(print("T#1m30s + TIME#250ms"), "T#1m30s + T#250ms");
  EXPECT_EQ(print("INT#-5"), "-INT#5");
  EXPECT_EQ(print("'it$'s $N'"), "'it$'s $N'");
  EXPECT_EQ(print("f(x := 1, y => z, NOT q => w)"), "f(x := 1, y => z, NOT q => w)");
  EXPECT_EQ(print("D#2024-01-31 = DATE#2024-01-31"), "D#2024-01-31 = D#2024-01-31");
  EXPECT_FALSE(diags.hasErrors());
}

}  // namespace
}  // namespace virtcom::plcopen::testing
