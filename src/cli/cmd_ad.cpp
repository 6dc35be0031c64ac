// `virtcom ad tables FILE.ad [--format text|markdown|csv]`: the LU table and the rule table of
// every diagram of an activity-diagram file (seed 002), as the decomposition produces them.
#include <iostream>

#include "cli/commands.hpp"
#include "cli/common.hpp"
#include "lang/ad/decompose.hpp"
#include "lang/ad/reader.hpp"
#include "lang/ad/tables.hpp"

namespace virtcom::cli {

namespace {

ExitCode printTables(const std::string& path, const std::string& formatName) {
  auto format = ad::tableFormatFromName(formatName);
  if (!format) {
    std::cerr << "virtcom ad tables: unknown format '" << formatName << "' (text, markdown, csv)\n";
    return ExitCode::Usage;
  }
  auto inputs = readSources({path});
  if (!inputs) return ExitCode::InputError;
  SourceManager sources;
  Diagnostics diags;
  uint32_t fileId = sources.addFile(path, inputs->front().text);
  ad::Program program = ad::readProgramFile(fileId, path, sources.text(fileId), diags);
  std::cerr << diags.render(sources);
  if (diags.hasErrors()) return ExitCode::InputError;
  std::vector<ad::DiagramTables> tables;
  for (const ad::Diagram& d : program.diagrams) tables.push_back(ad::decompose(d));
  std::cout << ad::formatTables(program, tables, *format);
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
  tables->add_option("--format", *format, "text (aligned columns), markdown or csv")->capture_default_str();
  tables->callback([file, format, setExit] { setExit(printTables(*file, *format)); });
  addAdFileCommands(*cmd, setExit);
  addAdRenderCommand(*cmd, setExit);
}

}  // namespace virtcom::cli
