#include <iostream>

#include "cli/commands.hpp"
#include "cli/common.hpp"
#include "cli/compile_library.hpp"

namespace virtcom::cli {

void addCheckCommand(CLI::App& app, std::function<void(ExitCode)> setExit) {
  auto files = std::make_shared<std::vector<std::string>>();
  CLI::App* cmd = app.add_subcommand("check", "Compile ST files and report every diagnostic (exit 0 clean, 1 on errors); "
                                               "files without a PROGRAM are checked as a library");
  cmd->add_option("files", *files, kSourceFilesHelp)->required()->check(CLI::ExistingFile);
  cmd->callback([files, setExit] {
    SourceManager sources;
    Diagnostics diags;
    auto module = compileLibraryFiles(*files, sources, diags);
    if (module && diags.warningCount() == 0)
      std::cerr << "ok: " << files->size() << " file(s), no diagnostics"
                << (module->programs.empty() ? " (a library: no PROGRAM)" : "") << "\n";
    setExit(module ? ExitCode::Ok : ExitCode::InputError);
  });
}

}  // namespace virtcom::cli
