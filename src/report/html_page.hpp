#pragma once
// The page every HTML file of report/ is: one self-contained document with the reports' inline
// stylesheet. Internal to src/report.
#include <string>

namespace virtcom::report {

// `<!DOCTYPE html>` up to and including `<main>`: charset, viewport, the escaped `title` and the
// stylesheet. Allocates.
std::string htmlPageStart(const std::string& title);

// Closes what htmlPageStart opened.
inline constexpr const char* kHtmlPageEnd = "</main>\n</body>\n</html>\n";

}  // namespace virtcom::report
