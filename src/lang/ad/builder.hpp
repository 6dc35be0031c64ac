#pragma once
// Internal to the two readers of diagram files (reader.cpp: the .ad text, xml_reader.cpp:
// AD-XML): both cut their input into words with locations, one element, port or arc at a time,
// and hand them to one ProgramBuilder, which checks names, kinds and presets and builds the
// model. So both forms accept exactly the same diagrams and report the same A0xx codes.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostics.hpp"
#include "lang/ad/diagram.hpp"

namespace virtcom::ad::detail {

// One word of a line (or one attribute value of an element) and where it starts.
struct Word {
  std::string_view text;
  SourceLocation loc;
};

std::string lowerAscii(std::string_view s);

class ProgramBuilder {
 public:
  ProgramBuilder(uint32_t fileId, Diagnostics& diags) : fileId_(fileId), diags_(diags) {}

  // Each takes the words of the text form's line, keyword first (`program NAME`,
  // `port NAME I|O|M [%ADDRESS]`, `diagram NAME`, `end_diagram`, `KEYWORD ID ...`).
  void program(const std::vector<Word>& w);
  void port(const std::vector<Word>& w);
  void openDiagram(const std::vector<Word>& w);
  void endDiagram(const std::vector<Word>& w);
  void node(NodeKind kind, const std::vector<Word>& w);
  // An arc between two element ids of the open diagram; resolved when the diagram closes, so
  // arcs may come before the elements they name.
  void arc(const Word& from, ArcKind kind, const Word& kindWord, const Word& to);
  // Closes an open diagram (reporting it, A001) and checks that a program was named.
  Program finish();

 private:
  struct PendingArc {
    Word from;
    ArcKind kind;
    Word kindWord, to;
  };

  bool expectCount(const std::vector<Word>& w, size_t min, size_t max, std::string_view form);
  bool expectIdentifier(const Word& word, std::string_view what);
  bool declare(const Word& name, std::string_view what);
  bool readNodeTail(Node& node, const std::vector<Word>& w);
  bool readBlock(Node& node, const std::vector<Word>& w, bool timer);
  bool readFunctionBlock(Node& node, const std::vector<Word>& w);
  bool readTimePreset(Node& node, const Word& word);
  bool readCountPreset(Node& node, const Word& word);
  void closeDiagram();
  std::optional<size_t> resolve(const Word& word);

  uint32_t fileId_;
  Diagnostics& diags_;
  Program program_;
  bool sawProgram_ = false;
  Diagram* diagram_ = nullptr;  // the open diagram (program_.diagrams is not resized while open)
  std::vector<PendingArc> arcs_;
  std::map<std::string, size_t> ids_;            // element id (lower case) -> node index
  std::map<std::string, SourceLocation> names_;  // every declared name in the file
};

}  // namespace virtcom::ad::detail
