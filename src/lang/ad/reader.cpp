// The line reader of .ad files; the words of each line go to the builder (builder.hpp), the
// structural checks are in check.cpp.
#include "lang/ad/reader.hpp"

#include <cctype>
#include <string>
#include <vector>

#include "lang/ad/builder.hpp"
#include "lang/ad/diagnostic_codes.hpp"

namespace virtcom::ad {

namespace {

using detail::Word;

// Cuts the text into lines and each line into words, and hands each line to the builder by its
// keyword (an arc is recognised by its arrow, `A -> B`).
class LineReader {
 public:
  LineReader(uint32_t fileId, Diagnostics& diags) : fileId_(fileId), diags_(diags), builder_(fileId, diags) {}

  Program read(std::string_view text) {
    uint32_t lineNo = 0;
    size_t pos = 0;
    while (pos <= text.size()) {
      size_t end = text.find('\n', pos);
      if (end == std::string_view::npos) end = text.size();
      readLine(text.substr(pos, end - pos), ++lineNo);
      pos = end + 1;
    }
    return builder_.finish();
  }

 private:
  std::vector<Word> split(std::string_view line, uint32_t lineNo) {
    std::vector<Word> words;
    size_t comment = line.find("//");
    if (comment != std::string_view::npos) line = line.substr(0, comment);
    size_t i = 0;
    while (i < line.size()) {
      if (std::isspace(static_cast<unsigned char>(line[i]))) { ++i; continue; }
      size_t start = i;
      while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      words.push_back({line.substr(start, i - start), {fileId_, lineNo, static_cast<uint32_t>(start + 1)}});
    }
    return words;
  }

  void readLine(std::string_view line, uint32_t lineNo) {
    std::vector<Word> w = split(line, lineNo);
    if (w.empty()) return;
    if (w.size() == 3) {
      if (auto arc = arcKindFromArrow(w[1].text)) return builder_.arc(w[0], *arc, w[1], w[2]);
    }
    std::string keyword = detail::lowerAscii(w[0].text);
    if (keyword == "program") return builder_.program(w);
    if (keyword == "port") return builder_.port(w);
    if (keyword == "diagram") return builder_.openDiagram(w);
    if (keyword == "end_diagram") return builder_.endDiagram(w);
    if (auto kind = nodeKindFromKeyword(keyword)) return builder_.node(*kind, w);
    diags_.error(diag::A002, w[0].loc, "unknown keyword '" + std::string(w[0].text) +
                                           "' (expected program, port, diagram, an element or an arc `A -> B`)");
  }

  uint32_t fileId_;
  Diagnostics& diags_;
  detail::ProgramBuilder builder_;
};

}  // namespace

Program readProgram(uint32_t fileId, std::string_view text, Diagnostics& diags) {
  size_t errorsBefore = diags.errorCount();
  Program program = LineReader(fileId, diags).read(text);
  if (diags.errorCount() == errorsBefore) checkProgram(program, diags);
  return program;
}

bool isDiagramPath(std::string_view path) {
  return path.size() >= 3 && path[path.size() - 3] == '.' && detail::lowerAscii(path.substr(path.size() - 2)) == "ad";
}

}  // namespace virtcom::ad
