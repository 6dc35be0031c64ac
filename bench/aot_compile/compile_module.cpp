// aot_compile_module FILE.st...: compiles ST files and loads them with aot::compileModule, as
// `virtcom exec --backend aot` does at start-up, and nothing else; prints how many translation
// units the module has and how many were compiled now (the rest came from the cache). The cache
// is $VIRTCOM_AOT_CACHE as for virtcom. bench/aot_compile/compile_cost.sh times it.
#include <fstream>
#include <iostream>
#include <sstream>

#include "aot/compile.hpp"
#include "lang/st/compiler.hpp"

int main(int argc, char** argv) {
  if (argc < 2 || std::string(argv[1]) == "--help") {
    std::cerr << "usage: aot_compile_module FILE.st...   (the AOT cache is $VIRTCOM_AOT_CACHE)\n";
    return argc < 2 ? 64 : 0;
  }
  std::vector<virtcom::st::SourceInput> inputs;
  for (int i = 1; i < argc; ++i) {
    std::ifstream in(argv[i], std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    if (!in) {
      std::cerr << "aot_compile_module: cannot read " << argv[i] << "\n";
      return 66;
    }
    inputs.push_back({argv[i], text.str()});
  }
  virtcom::SourceManager sources;
  virtcom::Diagnostics diags;
  const auto module = virtcom::st::compileProgram(inputs, sources, diags);
  if (!module) {
    std::cerr << diags.render(sources);
    return 65;
  }
  const virtcom::aot::CompileResult r = virtcom::aot::compileModule(*module);
  if (!r.code) {
    std::cerr << "aot_compile_module: " << r.error << "\n";
    return 1;
  }
  std::cout << r.units << " units, " << r.unitsCompiled << " compiled\n";
  return 0;
}
