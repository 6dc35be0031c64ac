// The table of standard functions (src/lang/st/declare/standard_functions.def) and the compiler
// agree: every name in it is reserved (E119) and callable, positionally and by its parameter
// names, and the user guide lists it.
#include "lang/st/declare/standard_functions.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "lang/st/compiler.hpp"
#include "lang/st/parse/lexer.hpp"

namespace virtcom::st {
namespace {

struct Compiled {
  SourceManager sources;
  Diagnostics diags;
  bool ok = false;
};

std::unique_ptr<Compiled> compile(const std::string& text) {
  auto c = std::make_unique<Compiled>();
  c->ok = compileProgram({{"main.st", text}}, c->sources, c->diags) != nullptr;
  return c;
}

// An argument input `index` of `fn` accepts: a variable for ADR/REF/SIZEOF, a selector for
// SEL/MUX, integers for string lengths and positions, text for the string functions, numbers
// otherwise.
std::string sampleArgument(const StandardFunction& fn, size_t index) {
  std::string_view param = listedParameter(fn.parameters, index);
  switch (fn.family) {
    case StandardFamily::Address: case StandardFamily::SizeOf: return "v";
    case StandardFamily::Selection: return index == 0 ? (fn.id == StandardFunctionId::SEL ? "TRUE" : "0") : "3";
    case StandardFamily::StringQuery: case StandardFamily::StringEdit: case StandardFamily::StringConcat:
      return param == "L" || param == "P" ? "1" : "'abc'";
    case StandardFamily::MathNative: case StandardFamily::MathNative2: case StandardFamily::Truncation:
    case StandardFamily::Scaling:
      return "0.5";
    default: return std::to_string(index + 2);
  }
}

// `fn(...)` with fn's least number of inputs, named if `named`, as the input of a MOVE call
// statement (AND, OR, XOR, NOT, MOD are functions only inside an expression).
std::string callOf(const StandardFunction& fn, bool named) {
  std::string call = std::string(fn.name) + "(";
  for (size_t i = 0; i < fn.minArgs; ++i) {
    if (i > 0) call += ", ";
    if (named) call += std::string(listedParameter(fn.parameters, i)) + " := ";
    call += sampleArgument(fn, i);
  }
  return "MOVE(" + call + "));";
}

// AND, OR, XOR, NOT and MOD are also operator keywords: a declaration of them is a syntax error.
bool isKeyword(std::string_view name) {
  Diagnostics diags;
  return lex(0, name, diags).front().kind != Tok::Identifier;
}

std::string program(const std::string& declarations, const std::string& body) {
  return "PROGRAM MAIN\nVAR\n  v : INT;\n" + declarations + "END_VAR\n" + body + "\nEND_PROGRAM\n";
}

TEST(StandardFunctions, TheTableHasNoDuplicatesAndSaneCounts) {
  for (size_t i = 0; i < standardFunctions().size(); ++i) {
    const StandardFunction& fn = standardFunctions()[i];
    EXPECT_LE(fn.minArgs, fn.maxArgs) << fn.name;
    EXPECT_LE(fn.maxArgs, kExtensible) << fn.name;
    EXPECT_EQ(static_cast<size_t>(fn.id), i) << fn.name;
    if (fn.naming == ParameterNaming::Listed) {
      EXPECT_FALSE(listedParameter(fn.parameters, fn.maxArgs - 1).empty()) << fn.name << " names too few inputs";
      EXPECT_TRUE(listedParameter(fn.parameters, fn.maxArgs).empty()) << fn.name << " names too many inputs";
    } else {
      EXPECT_TRUE(fn.parameters.empty()) << fn.name;
    }
    for (size_t j = 0; j < i; ++j) EXPECT_NE(standardFunctions()[j].name, fn.name);
  }
}

TEST(StandardFunctions, EveryNameIsReservedForVariables) {
  for (const StandardFunction& fn : standardFunctions()) {
    EXPECT_TRUE(isStandardFunctionName(fn.name)) << fn.name;
    auto c = compile(program("  " + std::string(fn.name) + " : INT;\n", ""));
    ASSERT_FALSE(c->ok) << fn.name;
    if (!isKeyword(fn.name)) {
      ASSERT_EQ(c->diags.all().size(), 1u) << fn.name << "\n" << c->diags.render(c->sources);
      EXPECT_EQ(c->diags.all()[0].code, "E119") << fn.name;
    }
  }
}

TEST(StandardFunctions, EveryFunctionIsCallable) {
  for (const StandardFunction& fn : standardFunctions()) {
    auto c = compile(program("", callOf(fn, false)));
    EXPECT_TRUE(c->ok && c->diags.all().empty()) << callOf(fn, false) << "\n" << c->diags.render(c->sources);
  }
}

TEST(StandardFunctions, ListedParametersBindByName) {
  for (const StandardFunction& fn : standardFunctions()) {
    if (fn.naming != ParameterNaming::Listed) continue;
    auto c = compile(program("", callOf(fn, true)));
    EXPECT_TRUE(c->ok && c->diags.all().empty()) << callOf(fn, true) << "\n" << c->diags.render(c->sources);
  }
}

TEST(StandardFunctions, ConversionsFollowTheNamingRule) {
  for (std::string name : {"INT_TO_REAL", "TIME_OF_DAY_TO_DINT", "TOD_TO_STRING", "TO_WSTRING", "BOOL_TO_LREAL"}) {
    EXPECT_TRUE(isStandardFunctionName(name)) << name;
    auto fn = findStandardFunction(name);
    ASSERT_TRUE(fn) << name;
    EXPECT_EQ(fn->family, StandardFamily::Conversion);
  }
  for (std::string name : {"INT_TO", "TO_", "FOO_TO_INT", "INT_TO_FOO", "_TO_INT", "TO_TO_INT", "MEMCPY", "__SYSTIME_NS"})
    EXPECT_FALSE(isStandardFunctionName(name)) << name;
}

TEST(StandardFunctions, TheUserGuideListsEveryFunction) {
  std::ifstream in(VIRTCOM_SOURCE_DIR "/docs/st-dialect.md", std::ios::binary);
  ASSERT_TRUE(in) << "cannot read docs/st-dialect.md";
  std::stringstream text;
  text << in.rdbuf();
  std::string page = text.str();
  size_t begin = page.find("\n## Standard functions\n");
  ASSERT_NE(begin, std::string::npos);
  std::string section = page.substr(begin, page.find("\n## ", begin + 1) - begin);
  auto isWordChar = [](char ch) { return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_'; };
  for (const StandardFunction& fn : standardFunctions()) {
    bool found = false;
    for (size_t at = section.find(fn.name); at != std::string::npos && !found; at = section.find(fn.name, at + 1))
      found = !isWordChar(section[at - 1]) && !isWordChar(section[at + fn.name.size()]);
    EXPECT_TRUE(found) << fn.name << " is missing from the standard functions of docs/st-dialect.md";
  }
}

}  // namespace
}  // namespace virtcom::st
