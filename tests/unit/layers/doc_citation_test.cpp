// Comments, READMEs and CMake files under src/ cite documents inside the repository: every
// `*.md` path they name must exist in the repo (relative to its root or to the citing file's
// folder), so a reader of a checkout can follow it (docs/architecture.md, "Adding a folder").
#include <gtest/gtest.h>

#include <regex>

#include "layer_table.hpp"

namespace virtcom::layers {
namespace {

namespace fs = std::filesystem;

// Inside the repo and there: `cited` taken from the repo root, or else from `citingFolder`.
bool citesInsideTheRepo(const std::string& cited, const fs::path& citingFolder) {
  if (cited.starts_with("/")) return false;
  const fs::path root = fs::path(sourceDir()).lexically_normal();
  for (const fs::path& base : {root, citingFolder}) {
    const fs::path candidate = (base / cited).lexically_normal();
    const std::string fromRoot = candidate.lexically_relative(root).generic_string();
    if (!fromRoot.empty() && !fromRoot.starts_with("..") && fs::exists(candidate)) return true;
  }
  return false;
}

TEST(DocCitations, EveryCitedDocumentIsInTheRepo) {
  // A path of a Markdown document: optional leading / or ../, folders, a name ending in .md.
  static const std::regex kDocPath(R"((?:/|\.\./)*(?:[A-Za-z0-9_.-]+/)*[A-Za-z0-9_-][A-Za-z0-9_.-]*\.md\b)");
  for (const auto& file : sourceTreeFiles()) {
    std::istringstream lines(test::readFile(file));
    std::string line;
    for (int number = 1; std::getline(lines, line); ++number) {
      for (std::sregex_iterator it(line.begin(), line.end(), kDocPath), end; it != end; ++it) {
        const std::string cited = it->str();
        if (!citesInsideTheRepo(cited, file.parent_path()))
          ADD_FAILURE() << repoPath(file) << ":" << number << ": cites " << cited
            << ", which is not a file of the repository: move what the code relies on into docs/ and cite that";
      }
    }
  }
}

}  // namespace
}  // namespace virtcom::layers
