// `virtcom export --plcopen OUT.xml FILES...`: the program as one PLCopen TC6 XML 2.01 project.
#include <sys/stat.h>

#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "cli/commands.hpp"
#include "cli/common.hpp"
#include "cli/compile_library.hpp"
#include "lang/plcopen/exporter.hpp"

namespace virtcom::cli {

namespace {

// The newest input's modification time (UTC), so exporting the same files twice gives the same
// bytes; TC6 requires a creationDateTime.
std::string newestModificationTime(const std::vector<std::string>& paths) {
  time_t newest = 0;
  for (const auto& path : paths) {
    struct stat info {};
    if (stat(path.c_str(), &info) == 0 && info.st_mtime > newest) newest = info.st_mtime;
  }
  std::tm utc{};
  gmtime_r(&newest, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &utc);
  return text;
}

}  // namespace

ExitCode exportPlcopen(const std::string& out, const std::string& name, const std::vector<std::string>& files) {
  {
    SourceManager sources;
    Diagnostics diags;
    // Only valid files are exported; a library (no PROGRAM) is valid.
    if (!compileLibraryFiles(files, sources, diags)) return ExitCode::InputError;
  }
  auto inputs = readSources(files);
  if (!inputs) return ExitCode::InputError;
  SourceManager sources;
  Diagnostics parseDiags;  // already shown by the compile above
  st::NodeId nextId = 0;
  std::vector<st::CompilationUnit> units = st::parseInputs(*inputs, sources, parseDiags, nextId);
  Diagnostics diags;
  std::vector<const st::CompilationUnit*> pointers;
  for (const auto& u : units) pointers.push_back(&u);
  plcopen::ExportOptions options;
  options.projectName = name.empty() ? std::filesystem::path(out).stem().string() : name;
  options.timestamp = newestModificationTime(files);
  std::string xml = plcopen::exportProject(pointers, options, diags);
  std::cerr << diags.render(sources);
  if (xml.empty()) return ExitCode::InputError;
  std::ofstream file(out, std::ios::binary);
  file << xml;
  if (!file.flush()) {
    std::cerr << out << ": error: cannot write the file\n";
    return ExitCode::InputError;
  }
  return ExitCode::Ok;
}

void addExportCommand(CLI::App& app, std::function<void(ExitCode)> setExit) {
  auto files = std::make_shared<std::vector<std::string>>();
  auto out = std::make_shared<std::string>();
  auto name = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("export", "Write the program (ST and PLCopen XML files) as a PLCopen TC6 XML 2.01 project");
  cmd->add_option("--plcopen", *out, "The PLCopen XML file to write")->required();
  cmd->add_option("--name", *name, "Project name in the contentHeader (default: the output file's stem)");
  cmd->add_option("files", *files, kSourceFilesHelp)->required()->check(CLI::ExistingFile);
  cmd->callback([files, out, name, setExit] { setExit(exportPlcopen(*out, *name, *files)); });
}

}  // namespace virtcom::cli
