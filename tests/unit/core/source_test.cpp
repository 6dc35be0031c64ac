#include <gtest/gtest.h>

#include "core/source.hpp"

namespace virtcom {
namespace {

TEST(SourceManager, AddFileReturnsConsecutiveIdsAndKeepsPathAndText) {
  SourceManager sources;
  EXPECT_EQ(sources.fileCount(), 0u);
  EXPECT_EQ(sources.addFile("a.st", "x"), 0u);
  EXPECT_EQ(sources.addFile("b.st", "y"), 1u);
  EXPECT_EQ(sources.fileCount(), 2u);
  EXPECT_EQ(sources.path(1), "b.st");
  EXPECT_EQ(sources.text(0), "x");
}

TEST(SourceManager, LineTextWithLfEndings) {
  SourceManager sources;
  uint32_t f = sources.addFile("a.st", "one\ntwo\nthree\n");
  EXPECT_EQ(sources.lineText(f, 1), "one");
  EXPECT_EQ(sources.lineText(f, 2), "two");
  EXPECT_EQ(sources.lineText(f, 3), "three");
  EXPECT_EQ(sources.lineText(f, 4), "");  // the empty line after the final newline
}

TEST(SourceManager, LineTextStripsCarriageReturnOfCrLf) {
  SourceManager sources;
  uint32_t f = sources.addFile("a.st", "one\r\ntwo\r\n\r\nfour");
  EXPECT_EQ(sources.lineText(f, 1), "one");
  EXPECT_EQ(sources.lineText(f, 2), "two");
  EXPECT_EQ(sources.lineText(f, 3), "");
  EXPECT_EQ(sources.lineText(f, 4), "four");
}

TEST(SourceManager, LastLineWithoutNewline) {
  SourceManager sources;
  uint32_t f = sources.addFile("a.st", "first\nlast");
  EXPECT_EQ(sources.lineText(f, 2), "last");
  EXPECT_EQ(sources.lineText(f, 3), "");
}

TEST(SourceManager, SingleLineAndEmptyFile) {
  SourceManager sources;
  uint32_t one = sources.addFile("one.st", "only");
  uint32_t empty = sources.addFile("empty.st", "");
  EXPECT_EQ(sources.lineText(one, 1), "only");
  EXPECT_EQ(sources.lineText(empty, 1), "");
  EXPECT_EQ(sources.lineText(empty, 2), "");
}

TEST(SourceManager, OutOfRangeIsEmpty) {
  SourceManager sources;
  uint32_t f = sources.addFile("a.st", "a\nb\n");
  EXPECT_EQ(sources.lineText(f, 0), "");
  EXPECT_EQ(sources.lineText(f, 99), "");
  EXPECT_EQ(sources.lineText(f + 1, 1), "");
  EXPECT_EQ(sources.lineText(0xffffffffu, 1), "");
}

TEST(SourceManager, LoneCarriageReturnInsideALineIsKept) {
  SourceManager sources;
  uint32_t f = sources.addFile("a.st", "a\rb\n");
  EXPECT_EQ(sources.lineText(f, 1), "a\rb");
}

}  // namespace
}  // namespace virtcom
