// Keeps the "Exit status" table of docs/diagnostics.md in sync with src/cli/exit_codes.def (row
// for row: status, name, meaning), and checks that every status the guide cites ("exit 3",
// "exit status 1") is one of them.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli/exit_code.hpp"
#include "support/read_file.hpp"

namespace virtcom::cli {
namespace {

struct Row {
  int status;
  std::string name;
  std::string meaning;
  bool operator==(const Row&) const = default;
};

std::ostream& operator<<(std::ostream& os, const Row& r) { return os << r.status << " " << r.name << ": " << r.meaning; }

const std::vector<Row> kTable = {
#define X(name, value, meaning) {value, #name, meaning},
#include "cli/exit_codes.def"
#undef X
};

const std::filesystem::path kRoot = VIRTCOM_SOURCE_DIR;

// The rows `| status | `Name` | meaning |` of the section "## Exit status", in page order.
std::vector<Row> documentedRows() {
  std::istringstream page(test::readFile(kRoot / "docs/diagnostics.md"));
  const std::regex row(R"(\| (\d+) \| `(\w+)` \| (.*) \|)");
  std::vector<Row> rows;
  bool inSection = false;
  std::string line;
  while (std::getline(page, line)) {
    if (line.rfind("#", 0) == 0) inSection = line == "## Exit status";
    std::smatch m;
    if (inSection && std::regex_match(line, m, row)) rows.push_back({std::stoi(m[1]), m[2], m[3]});
  }
  return rows;
}

TEST(ExitCodesDoc, TheTableListsEveryStatusOfTheEnum) {
  EXPECT_EQ(documentedRows(), kTable) << "docs/diagnostics.md, \"## Exit status\", against src/cli/exit_codes.def";
}

TEST(ExitCodesDoc, EveryStatusTheGuideCitesExists) {
  std::set<int> statuses;
  for (const Row& r : kTable) statuses.insert(r.status);
  std::vector<std::filesystem::path> pages{kRoot / "README.md"};
  for (const auto& entry : std::filesystem::directory_iterator(kRoot / "docs"))
    if (entry.path().extension() == ".md") pages.push_back(entry.path());
  const std::regex cite(R"(\bexit(?:\s+(?:status|code))?\s+(\d+)\b)", std::regex::icase);
  for (const auto& page : pages) {
    const std::string text = test::readFile(page);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), cite); it != std::sregex_iterator(); ++it)
      EXPECT_TRUE(statuses.count(std::stoi((*it)[1]))) << page.filename().string() << " cites '" << it->str()
                                                       << "', which is not in src/cli/exit_codes.def";
  }
}

TEST(ExitCodes, TheEnumHasTheTablesValues) {
  EXPECT_EQ(static_cast<int>(ExitCode::Ok), 0);
  EXPECT_EQ(static_cast<int>(ExitCode::InputError), 1);
  EXPECT_EQ(static_cast<int>(ExitCode::PlcFault), 2);
  EXPECT_EQ(static_cast<int>(ExitCode::RunStopped), 3);
  EXPECT_EQ(static_cast<int>(ExitCode::Usage), 64);
}

}  // namespace
}  // namespace virtcom::cli
