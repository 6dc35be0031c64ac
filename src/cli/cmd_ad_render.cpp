// `virtcom ad render FILE.ad --svg OUT.svg [--dot OUT.dot] [--diagram NAME]`: the picture of the
// diagrams of an activity-diagram file with the symbols of seed 002, laid out top to bottom by
// Graphviz; all diagrams side by side, or only the one `--diagram` names.
#include <iostream>

#include "cli/commands.hpp"
#include "cli/common.hpp"
#include "cli/graphviz_svg.hpp"
#include "lang/ad/dot.hpp"

namespace virtcom::cli {

namespace {

struct RenderOptions {
  std::string file, svg, dot, diagram;
};

// The diagrams to draw: all, or the one named (exact spelling); empty after an error message.
std::vector<const ad::Diagram*> selectDiagrams(const ad::Program& program, const std::string& name) {
  std::vector<const ad::Diagram*> out;
  std::string names;
  for (const ad::Diagram& d : program.diagrams) {
    if (name.empty() || d.name == name) out.push_back(&d);
    names += (names.empty() ? "" : ", ") + d.name;
  }
  if (out.empty()) std::cerr << "virtcom ad render: no diagram '" << name << "' (the file has: " << names << ")\n";
  return out;
}

ExitCode render(const RenderOptions& o) {
  if (o.svg.empty() && o.dot.empty()) {
    std::cerr << "virtcom ad render: nothing to write: give --svg and/or --dot\n";
    return ExitCode::Usage;
  }
  std::optional<ad::Program> program = readDiagramFile(o.file);
  if (!program) return ExitCode::InputError;
  std::vector<const ad::Diagram*> diagrams = selectDiagrams(*program, o.diagram);
  if (diagrams.empty()) return ExitCode::Usage;
  const std::string dot = ad::toDot(*program, diagrams);
  if (!o.dot.empty() && !writeFile(o.dot, dot)) return ExitCode::Usage;
  if (o.svg.empty()) return ExitCode::Ok;
  std::expected<std::string, std::string> svg = renderSvg(dot);
  if (!svg) {
    std::cerr << "virtcom ad render: " << svg.error() << "\n";
    return ExitCode::InputError;
  }
  return writeFile(o.svg, *svg) ? ExitCode::Ok : ExitCode::Usage;
}

}  // namespace

void addAdRenderCommand(CLI::App& ad, std::function<void(ExitCode)> setExit) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* cmd = ad.add_subcommand(
      "render", "Draw the diagrams of FILE with the symbols of seed 002 (top to bottom, laid out by Graphviz dot)");
  cmd->add_option("file", o->file, "an activity-diagram file (.ad or .adxml)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--svg", o->svg, "the SVG file to write: every diagram side by side, one frame each");
  cmd->add_option("--dot", o->dot, "also (or only) write the Graphviz DOT text the picture is laid out from");
  cmd->add_option("--diagram", o->diagram, "draw only this diagram (its name as written after `diagram`)");
  cmd->callback([o, setExit] { setExit(render(*o)); });
}

}  // namespace virtcom::cli
