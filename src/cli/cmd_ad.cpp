// `virtcom ad tables FILE.ad [--format text|markdown|csv|html]`: the LU table and the rule table of
// every diagram of an activity-diagram file (seed 002), as the decomposition produces them.
#include <iostream>

#include "cli/commands.hpp"
#include "cli/common.hpp"
#include "lang/ad/decompose.hpp"
#include "lang/ad/tables.hpp"
#include "report/diagram_tables.hpp"

namespace virtcom::cli {

namespace {

// A page of its own, drawn by report/ as the run report's diagram section is (without counts).
std::string tablesPage(const ad::Program& program, const std::vector<ad::DiagramTables>& tables) {
  std::vector<report::DiagramTablesSection> sections;
  for (const ad::DiagramTables& t : tables) sections.push_back({program.name, t.diagram->name, ad::luTable(t), ad::ruleTable(t), {}});
  return report::diagramTablesPage(program.name, sections);
}

ExitCode printTables(const std::string& path, const std::string& formatName) {
  auto format = ad::tableFormatFromName(formatName);
  if (!format && formatName != "html") {
    std::cerr << "virtcom ad tables: unknown format '" << formatName << "' (text, markdown, csv, html)\n";
    return ExitCode::Usage;
  }
  std::optional<ad::Program> program = readDiagramFile(path);
  if (!program) return ExitCode::InputError;
  std::vector<ad::DiagramTables> tables;
  for (const ad::Diagram& d : program->diagrams) tables.push_back(ad::decompose(d));
  std::cout << (format ? ad::formatTables(*program, tables, *format) : tablesPage(*program, tables));
  return ExitCode::Ok;
}

}  // namespace

void addAdCommand(CLI::App& app, std::function<void(ExitCode)> setExit) {
  CLI::App* cmd = app.add_subcommand("ad", "Activity diagrams (.ad): decomposition into logic units and rules");
  cmd->require_subcommand(1);
  auto file = std::make_shared<std::string>();
  auto format = std::make_shared<std::string>("text");
  CLI::App* tables = cmd->add_subcommand("tables", "Print the LU table and the rule table of every diagram of FILE");
  tables->add_option("file", *file, "an activity-diagram file (.ad or .adxml)")->required()->check(CLI::ExistingFile);
  tables->add_option("--format", *format, "text (aligned columns), markdown, csv, or html (a self-contained page in the style of the run report)")
      ->capture_default_str();
  tables->callback([file, format, setExit] { setExit(printTables(*file, *format)); });
  addAdFileCommands(*cmd, setExit);
  addAdRenderCommand(*cmd, setExit);
}

}  // namespace virtcom::cli
