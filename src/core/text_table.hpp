#pragma once
// A titled table of text cells: how a front end hands a table it computed (the LU and rule tables
// of an activity diagram) to the writers that render it (terminal, Markdown, CSV in lang/ad; HTML
// and JSON in report/), so that report/ renders it without knowing the front end.
#include <string>
#include <vector>

namespace virtcom {

struct TextTable {
  std::string title;                           // "LU table"
  std::vector<std::string> header;             // column names
  std::vector<std::vector<std::string>> rows;  // each as many cells as the header
};

}  // namespace virtcom
