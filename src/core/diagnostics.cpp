#include "core/diagnostics.hpp"

#include <algorithm>

namespace virtcom {

void Diagnostics::report(Severity sev, std::string_view code, SourceLocation loc, std::string message) {
  if (sev == Severity::Error) ++errors_;
  if (sev == Severity::Warning) ++warnings_;
  list_.push_back(Diagnostic{sev, code, loc, std::move(message)});
}

void Diagnostics::sortByLocation() {
  std::stable_sort(list_.begin(), list_.end(), [](const Diagnostic& a, const Diagnostic& b) {
    if (a.loc.fileId != b.loc.fileId) return a.loc.fileId < b.loc.fileId;
    if (a.loc.line != b.loc.line) return a.loc.line < b.loc.line;
    return a.loc.col < b.loc.col;
  });
}

void Diagnostics::moveFilesFirst(uint32_t firstFileId, uint32_t endFileId) {
  std::stable_partition(list_.begin(), list_.end(), [&](const Diagnostic& d) {
    return d.loc.fileId >= firstFileId && d.loc.fileId < endFileId;
  });
}

static const char* severityName(Severity s) {
  switch (s) {
    case Severity::Error: return "error";
    case Severity::Warning: return "warning";
    case Severity::Note: return "note";
  }
  return "error";
}

std::string renderDiagnostic(const Diagnostic& d, const SourceManager& sources) {
  std::string out;
  bool hasFile = d.loc.fileId < sources.fileCount();
  if (hasFile) {
    out += sources.path(d.loc.fileId);
    if (d.loc.line > 0) out += ":" + std::to_string(d.loc.line) + ":" + std::to_string(d.loc.col);
    out += ": ";
  }
  out += severityName(d.severity);
  if (!d.code.empty()) out += "[" + std::string(d.code) + "]";
  out += ": " + d.message + "\n";
  if (hasFile && d.loc.line > 0) {
    std::string_view line = sources.lineText(d.loc.fileId, d.loc.line);
    if (!line.empty()) {
      out += "  " + std::string(line) + "\n  ";
      for (uint32_t i = 1; i < d.loc.col && i <= line.size(); ++i) out += line[i - 1] == '\t' ? '\t' : ' ';
      out += "^\n";
    }
  }
  return out;
}

std::string Diagnostics::render(const SourceManager& sources) const {
  std::string out;
  for (const auto& d : list_) out += renderDiagnostic(d, sources);
  if (!list_.empty())
    out += std::to_string(errors_) + " error(s), " + std::to_string(warnings_) + " warning(s)\n";
  return out;
}

}  // namespace virtcom
