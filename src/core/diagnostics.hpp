#pragma once
// User-facing problems as values: collected, never thrown, rendered as
// `file:line:col: error[CODE]: message` followed by the source line and a caret.
#include <string>
#include <string_view>
#include <vector>

#include "core/source.hpp"

namespace virtcom {

enum class Severity { Error, Warning, Note };

struct Diagnostic {
  Severity severity = Severity::Error;
  std::string_view code;  // stable code such as "E012"; points at static storage
  SourceLocation loc;
  std::string message;
};

class Diagnostics {
 public:
  void report(Severity sev, std::string_view code, SourceLocation loc, std::string message);
  void error(std::string_view code, SourceLocation loc, std::string message) {
    report(Severity::Error, code, loc, std::move(message));
  }
  void warning(std::string_view code, SourceLocation loc, std::string message) {
    report(Severity::Warning, code, loc, std::move(message));
  }
  size_t errorCount() const { return errors_; }
  size_t warningCount() const { return warnings_; }
  bool hasErrors() const { return errors_ > 0; }
  const std::vector<Diagnostic>& all() const { return list_; }
  // Sorts by file, line, column (stable), so output order does not depend on pass order.
  void sortByLocation();
  // Moves the diagnostics of files [firstFileId, endFileId) before the others, each group keeping
  // its order: a root cause in those files (a PLC program that does not compile) is read first.
  void moveFilesFirst(uint32_t firstFileId, uint32_t endFileId);
  // Renders every diagnostic with its quoted source line and caret; ends with a summary line
  // when there is at least one diagnostic.
  std::string render(const SourceManager& sources) const;

 private:
  std::vector<Diagnostic> list_;
  size_t errors_ = 0;
  size_t warnings_ = 0;
};

std::string renderDiagnostic(const Diagnostic& d, const SourceManager& sources);

}  // namespace virtcom
