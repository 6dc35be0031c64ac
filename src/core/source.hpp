#pragma once
// Source files loaded for compilation and the locations that point into them.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace virtcom {

inline constexpr uint32_t kNoFile = 0xffffffffu;

// A position in a loaded source file. Lines and columns are 1-based; line 0 means "the file as
// a whole"; fileId kNoFile means "no file" (a whole-program diagnostic).
struct SourceLocation {
  uint32_t fileId = 0;
  uint32_t line = 0;
  uint32_t col = 0;
};

// Owns the text of every file of a compilation so diagnostics can quote the offending line.
class SourceManager {
 public:
  // Adds a file and returns its id. Never fails; the text is copied.
  uint32_t addFile(std::string path, std::string text);
  const std::string& path(uint32_t fileId) const { return files_[fileId].path; }
  const std::string& text(uint32_t fileId) const { return files_[fileId].text; }
  // The text of a 1-based line without its line terminator; empty if out of range.
  std::string_view lineText(uint32_t fileId, uint32_t line) const;
  size_t fileCount() const { return files_.size(); }

 private:
  struct File {
    std::string path;
    std::string text;
    std::vector<uint32_t> lineStarts;
  };
  std::vector<File> files_;
};

}  // namespace virtcom
