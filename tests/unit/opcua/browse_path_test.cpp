// Browse paths as a cell file writes them (browse_path.hpp): the text form of OPC 10000-4
// Annex A.2 from the Objects folder, its errors with the character and the expected form, and
// the BrowsePath a TranslateBrowsePathsToNodeIds request carries (golden bytes).
#include "proto/opcua/browse_path.hpp"

#include <gtest/gtest.h>

#include "hex_bytes.hpp"

namespace virtcom::proto::opcua {
namespace {

std::vector<BrowsePathElement> parsed(std::string_view text) {
  auto path = parseBrowsePath(text);
  EXPECT_TRUE(path) << path.error();
  return path ? *path : std::vector<BrowsePathElement>{};
}

std::string error(std::string_view text) {
  auto path = parseBrowsePath(text);
  EXPECT_FALSE(path) << text;
  return path ? "" : path.error();
}

TEST(OpcuaBrowsePath, ABrowsePathBeginsWithASlashOrADot) {
  EXPECT_TRUE(isBrowsePath("/4:MAIN/4:x"));
  EXPECT_TRUE(isBrowsePath(".4:x"));
  EXPECT_FALSE(isBrowsePath("ns=4;s=MAIN.x"));
  EXPECT_FALSE(isBrowsePath("MAIN.x"));
}

TEST(OpcuaBrowsePath, ElementsAreHierarchicalOrAggregatesWithTheirNamespace) {
  auto path = parsed("/4:MAIN/4:point.4:x.Name");
  ASSERT_EQ(path.size(), 4u);
  EXPECT_FALSE(path[0].aggregates);
  EXPECT_EQ(path[0].name, (QualifiedName{4, "MAIN"}));
  EXPECT_FALSE(path[1].aggregates);
  EXPECT_EQ(path[1].name, (QualifiedName{4, "point"}));
  EXPECT_TRUE(path[2].aggregates);
  EXPECT_EQ(path[2].name, (QualifiedName{4, "x"}));
  EXPECT_TRUE(path[3].aggregates);
  EXPECT_EQ(path[3].name, (QualifiedName{0, "Name"})) << "no index: namespace 0";
}

TEST(OpcuaBrowsePath, AnAmpersandEscapesReservedCharacters) {
  auto path = parsed("/3:\"DB&.1\"/3:a&&b&:c/12abc");
  ASSERT_EQ(path.size(), 3u);
  EXPECT_EQ(path[0].name, (QualifiedName{3, "\"DB.1\""}));
  EXPECT_EQ(path[1].name, (QualifiedName{3, "a&b:c"}));
  EXPECT_EQ(path[2].name, (QualifiedName{0, "12abc"})) << "digits without ':' are part of the name";
}

TEST(OpcuaBrowsePath, MistakesNameTheCharacterAndTheExpectedForm) {
  EXPECT_EQ(error("/4:MAIN//4:x"), "'/4:MAIN//4:x' at character 9: a browse name is missing (expected /NS:NAME elements from the Objects folder, e.g. /4:MAIN/4:x)");
  EXPECT_EQ(error("/4:"), "'/4:' at character 4: a browse name is missing (expected /NS:NAME elements from the Objects folder, e.g. /4:MAIN/4:x)");
  EXPECT_EQ(error("/4:a:b"), "'/4:a:b' at character 5: ':' is reserved in a browse name; write it as '&:'");
  EXPECT_EQ(error("/4:a&"), "'/4:a&' at character 5: '&' escapes the character after it, and none follows");
  EXPECT_EQ(error("/<Organizes>4:a"),
            "'/<Organizes>4:a' at character 2: reference types in <...> are not supported; '/' follows hierarchical references, '.' aggregates");
  EXPECT_EQ(error("/70000:a"), "'/70000:a' at character 2: namespace index above 65535");
  EXPECT_EQ(error("4:a"), "'4:a' at character 1: '/' or '.' expected before a browse name (expected /NS:NAME elements from the Objects folder, e.g. /4:MAIN/4:x)");
  EXPECT_EQ(error(""), "'': an empty browse path (expected /NS:NAME elements from the Objects folder, e.g. /4:MAIN/4:x)");
}

TEST(OpcuaBrowsePath, ABrowsePathStartsAtObjectsAndFollowsForwardReferencesWithSubtypes) {
  std::vector<uint8_t> out;
  Writer w(out);
  encodeBrowsePath(w, parsed("/4:a.b"));
  // StartingNode i=85 (two-byte form), 2 elements: {i=33 HierarchicalReferences, forward,
  // subtypes, 4:"a"}, {i=44 Aggregates, forward, subtypes, 0:"b"}.
  EXPECT_EQ(testing::hex(out), "00 55 02 00 00 00 00 21 00 01 04 00 01 00 00 00 61 00 2C 00 01 00 00 01 00 00 00 62");
}

}  // namespace
}  // namespace virtcom::proto::opcua
