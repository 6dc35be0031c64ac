// JUnit XML: cases grouped by file, in run order.
#include "scenario/junit.hpp"

#include <cstdio>
#include <sstream>

namespace virtcom::scenario {

namespace {

// Attribute and text escaping; control characters XML 1.0 cannot hold become spaces.
std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += (static_cast<unsigned char>(c) < 0x20 && c != '\n' && c != '\t') ? ' ' : c;
    }
  }
  return out;
}

std::string seconds(int64_t ns) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", static_cast<double>(ns) * 1e-9);
  return text;
}

struct Counts {
  size_t tests = 0, failures = 0, errors = 0, skipped = 0;
  int64_t wallNs = 0;
  void add(const CaseResult& r) {
    ++tests;
    failures += r.verdict == Verdict::Fail || r.verdict == Verdict::UnexpectedPass;
    errors += r.verdict == Verdict::Error;
    skipped += r.verdict == Verdict::ExpectedFail;
    wallNs += r.wallNs;
  }
  std::string attributes() const {
    return "tests=\"" + std::to_string(tests) + "\" failures=\"" + std::to_string(failures) + "\" errors=\"" + std::to_string(errors) +
           "\" skipped=\"" + std::to_string(skipped) + "\" time=\"" + seconds(wallNs) + "\"";
  }
};

std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + (line.ends_with('\n') ? "" : "\n");
  return text;
}

void writeCase(std::ostream& out, const CaseResult& r) {
  out << "    <testcase name=\"" << escape(r.spec.name) << "\" classname=\"" << escape(r.spec.classname) << "\" time=\"" << seconds(r.wallNs)
      << "\"";
  const std::string first = r.messages.empty() ? std::string() : r.messages.front().substr(0, r.messages.front().find('\n'));
  const char* element = r.verdict == Verdict::Error ? "error" : r.verdict == Verdict::ExpectedFail ? "skipped" : "failure";
  if (r.verdict == Verdict::Pass) {
    out << "/>\n";
    return;
  }
  out << ">\n      <" << element << " message=\"" << escape(r.verdict == Verdict::ExpectedFail ? "xfail: " + first : first) << "\"";
  if (r.verdict != Verdict::ExpectedFail) out << " type=\"" << (r.verdict == Verdict::Error ? "scenario" : "assertion") << "\"";
  out << ">" << escape(joined(r.messages) + "run: " + r.runEnd) << "</" << element << ">\n    </testcase>\n";
}

}  // namespace

std::string junitXml(const std::vector<CaseResult>& results) {
  Counts total;
  for (const CaseResult& r : results) total.add(r);
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"virtcom test\" " << total.attributes() << ">\n";
  for (size_t i = 0; i < results.size();) {
    size_t end = i;
    Counts suite;
    while (end < results.size() && results[end].spec.file == results[i].spec.file) suite.add(results[end++]);
    out << "  <testsuite name=\"" << escape(results[i].spec.classname) << "\" " << suite.attributes() << ">\n";
    for (; i < end; ++i) writeCase(out, results[i]);
    out << "  </testsuite>\n";
  }
  out << "</testsuites>\n";
  return out.str();
}

}  // namespace virtcom::scenario
