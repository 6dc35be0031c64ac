// `virtcom ad convert` (the .ad text and AD-XML, both ways) and `virtcom ad export` (the lowered
// program as ST, or as a PLCopen TC6 project with one LD rung per rule), subcommands of `ad`.
#include <iostream>

#include "cli/commands.hpp"
#include "cli/common.hpp"
#include "lang/ad/lower.hpp"
#include "lang/ad/writer.hpp"
#include "lang/syntax/printer.hpp"

namespace virtcom::cli {

namespace {

// What `ad convert` and `ad export` give back after writing a file.
ExitCode written(bool ok) { return ok ? ExitCode::Ok : ExitCode::InputError; }

ExitCode convert(const std::string& path, const std::string& xmlOut, const std::string& adOut) {
  if (xmlOut.empty() == adOut.empty()) {
    std::cerr << "virtcom ad convert: give exactly one of --xml OUT.adxml and --ad OUT.ad\n";
    return ExitCode::Usage;
  }
  auto program = readDiagramFile(path);
  if (!program) return ExitCode::InputError;
  return written(xmlOut.empty() ? writeFile(adOut, ad::formatText(*program)) : writeFile(xmlOut, ad::formatXml(*program)));
}

// The program as the compiler sees it: the lowered PROGRAM and its ACTIONs, printed.
ExitCode exportSt(const std::string& path, const std::string& out) {
  auto program = readDiagramFile(path);
  if (!program) return ExitCode::InputError;
  st::NodeId nextId = 0;
  st::CompilationUnit unit = ad::lowerProgram(*program, 0, nextId);
  return written(writeFile(out, "(* " + program->name + ": lowered from " + path + " by virtcom ad export *)\n" +
                                    st::printPou(*unit.pous.front())));
}

ExitCode exportDiagrams(const std::string& path, const std::string& stOut, const std::string& plcopenOut) {
  if (stOut.empty() && plcopenOut.empty()) {
    std::cerr << "virtcom ad export: give --st OUT.st and/or --plcopen OUT.xml\n";
    return ExitCode::Usage;
  }
  if (!stOut.empty()) {
    if (ExitCode code = exportSt(path, stOut); code != ExitCode::Ok) return code;
  }
  return plcopenOut.empty() ? ExitCode::Ok : exportPlcopen(plcopenOut, "", {path});
}

}  // namespace

void addAdFileCommands(CLI::App& ad, std::function<void(ExitCode)> setExit) {
  auto file = std::make_shared<std::string>();
  auto xmlOut = std::make_shared<std::string>(), adOut = std::make_shared<std::string>();
  CLI::App* convertCmd = ad.add_subcommand("convert", "Convert FILE between the .ad text and AD-XML (.adxml)");
  convertCmd->add_option("file", *file, "an activity-diagram file (.ad or .adxml)")->required()->check(CLI::ExistingFile);
  convertCmd->add_option("--xml", *xmlOut, "write the diagrams as AD-XML to this file (.adxml)");
  convertCmd->add_option("--ad", *adOut, "write the diagrams as normalised .ad text to this file");
  convertCmd->callback([=] { setExit(convert(*file, *xmlOut, *adOut)); });

  auto exportFile = std::make_shared<std::string>();
  auto stOut = std::make_shared<std::string>(), plcopenOut = std::make_shared<std::string>();
  CLI::App* exportCmd = ad.add_subcommand("export", "Export FILE for a real PLC: as Structured Text and/or as PLCopen XML with ladder (LD) rungs");
  exportCmd->add_option("file", *exportFile, "an activity-diagram file (.ad or .adxml)")->required()->check(CLI::ExistingFile);
  exportCmd->add_option("--st", *stOut, "write the program (one PROGRAM, one ACTION per diagram) as ST to this file");
  exportCmd->add_option("--plcopen", *plcopenOut,
                        "write a PLCopen TC6 XML 2.01 project to this file, each diagram an ACTION with an LD body, one rung per rule");
  exportCmd->callback([=] { setExit(exportDiagrams(*exportFile, *stOut, *plcopenOut)); });
}

}  // namespace virtcom::cli
