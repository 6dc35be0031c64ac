// Cobertura XML (report/coverage.hpp), after cobertura's coverage-04.dtd.
#include <filesystem>
#include <map>
#include <string>

#include "report/coverage.hpp"
#include "report/coverage_files.hpp"
#include "report/text_util.hpp"

namespace virtcom::report {

using detail::FileLines;
using detail::PouLines;

namespace {

std::string rate(const CoverageRatio& r) {
  return r.total == 0 ? std::string("1") : formatFixed(static_cast<double>(r.hit) / r.total, 4);
}

// Appended piece by piece: `" " + std::string(name)` trips GCC 12's -Wrestrict false positive.
std::string attr(std::string_view name, std::string_view value) {
  std::string out(" ");
  out.append(name).append("=\"").append(escapeHtml(value)).append("\"");
  return out;
}

struct ClassXml {
  std::string text;
  CoverageRatio lines, branches;
};

// One <class>: its lines, those with decisions carrying their arms' coverage.
ClassXml classXml(const FileLines& file, const PouLines& pou) {
  ClassXml c;
  std::map<uint32_t, CoverageRatio> armsByLine;
  for (const detail::Decision& d : pou.decisions)
    for (uint64_t count : d.arms) armsByLine[d.line].add(count > 0);
  std::string lines;
  for (const auto& [line, count] : pou.lines) {
    c.lines.add(count > 0);
    lines += "          <line" + attr("number", std::to_string(line)) + attr("hits", std::to_string(count));
    auto arms = armsByLine.find(line);
    if (arms == armsByLine.end()) {
      lines += attr("branch", "false") + "/>\n";
      continue;
    }
    const CoverageRatio& r = arms->second;
    c.branches.hit += r.hit;
    c.branches.total += r.total;
    const std::string percent = std::to_string(r.total ? r.hit * 100 / r.total : 100);
    lines += attr("branch", "true") +
             attr("condition-coverage", percent + "% (" + std::to_string(r.hit) + "/" + std::to_string(r.total) + ")") +
             "/>\n";
  }
  c.text = "      <class" + attr("name", pou.name) + attr("filename", file.path) + attr("line-rate", rate(c.lines)) +
           attr("branch-rate", rate(c.branches)) + attr("complexity", "0") + ">\n        <methods/>\n        <lines>\n" +
           lines + "        </lines>\n      </class>\n";
  return c;
}

}  // namespace

std::string coberturaXml(const CoverageData& data) {
  // Packages are directories ("." for files given without one), in name order.
  std::map<std::string, std::vector<ClassXml>> packages;
  for (const FileLines& file : detail::groupByFile(data)) {
    std::string dir = std::filesystem::path(file.path).parent_path().generic_string();
    for (const PouLines& pou : file.pous) packages[dir.empty() ? "." : dir].push_back(classXml(file, pou));
  }
  CoverageRatio lines, branches;
  std::string body;
  for (const auto& [name, classes] : packages) {
    CoverageRatio pl, pb;
    std::string text;
    for (const ClassXml& c : classes) {
      pl.hit += c.lines.hit, pl.total += c.lines.total;
      pb.hit += c.branches.hit, pb.total += c.branches.total;
      text += c.text;
    }
    lines.hit += pl.hit, lines.total += pl.total;
    branches.hit += pb.hit, branches.total += pb.total;
    body += "    <package" + attr("name", name) + attr("line-rate", rate(pl)) + attr("branch-rate", rate(pb)) +
            attr("complexity", "0") + ">\n      <classes>\n" + text + "      </classes>\n    </package>\n";
  }
  return "<?xml version=\"1.0\" ?>\n"
         "<!DOCTYPE coverage SYSTEM \"http://cobertura.sourceforge.net/xml/coverage-04.dtd\">\n"
         "<coverage" + attr("line-rate", rate(lines)) + attr("branch-rate", rate(branches)) +
         attr("lines-covered", std::to_string(lines.hit)) + attr("lines-valid", std::to_string(lines.total)) +
         attr("branches-covered", std::to_string(branches.hit)) + attr("branches-valid", std::to_string(branches.total)) +
         attr("complexity", "0") + attr("version", "virtcom") + attr("timestamp", "0") +
         ">\n  <sources>\n    <source>.</source>\n  </sources>\n  <packages>\n" + body + "  </packages>\n</coverage>\n";
}

}  // namespace virtcom::report
