#pragma once
// The scratch tree of the file-based fuzz targets (cell, scenario, process model, sweep): their
// readers take a path and resolve the files a YAML names (`plc: sources`, `mapping:`, `extends:`,
// a scenario's `cell:`) relative to it. So that a mutated input can neither read a file of the
// machine nor depend on the checkout, each fuzzer process gets a private copy of the checkout's
// examples/, lib/ and tests/e2e/data/ (regular files only: no symlink leads out), writes every
// input inside it, and skips (returns -1 for) any input naming a file that lies outside it. The
// tree is removed when the process exits.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "cell/yaml_config.hpp"
#include "core/config_node.hpp"

#ifndef VIRTCOM_SOURCE_DIR
#error "VIRTCOM_SOURCE_DIR (the checkout the scratch tree copies from) must be defined"
#endif

namespace virtcom::fuzz {

// Where each target writes its input in the copy. A cell beside the drive example cells and a
// scenario beside the gearbox's, so the seeds name the copy's files as the examples do.
inline constexpr const char* kCellInput = "examples/drives/g120/fuzz_cell.yaml";
inline constexpr const char* kScenarioInput = "examples/gearbox-cell/tests/fuzz_scenario.yaml";
inline constexpr const char* kProcessModelInput = "examples/gearbox-cell/fuzz_process.yaml";
inline constexpr const char* kSweepInput = "examples/gearbox-cell/fuzz_sweep.yaml";
// The inputs the loader may read as a cell file (a scenario's `cell:` may name itself).
inline constexpr const char* kLoadedAsCell[] = {kCellInput, kScenarioInput};

class Scratch {
 public:
  // The process's tree, made at the first call.
  static const Scratch& get() {
    static const Scratch scratch;
    return scratch;
  }

  const std::filesystem::path& root() const { return root_; }

  // Writes the input to `relative`, one of the k*Input paths above.
  std::string write(const std::string& relative, const uint8_t* data, size_t size) const {
    const std::filesystem::path p = root_ / relative;
    std::ofstream(p, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    return p.string();
  }

  // True if every scalar under a key that names a file, anywhere in `node`, resolves from
  // `dir` to a path inside the tree (lexically: the tree holds no symlinks). A NUL byte would
  // cut the path the reader opens short of the one checked here: such names are outside too.
  bool namesOnlyInside(const ConfigNode& node, const std::filesystem::path& dir) const {
    for (const auto& [key, value] : node.entries())
      if (isFileKey(key) ? !allInside(value, dir) : !namesOnlyInside(value, dir)) return false;
    for (const ConfigNode& item : node.items())
      if (!namesOnlyInside(item, dir)) return false;
    return true;
  }

 private:
  Scratch() {
    std::string pattern = (std::filesystem::temp_directory_path() / "virtcom-fuzz-XXXXXX").string();
    if (!mkdtemp(pattern.data())) std::abort();
    root_ = std::filesystem::canonical(pattern);
    const std::filesystem::path source(VIRTCOM_SOURCE_DIR);
    for (const char* dir : {"examples", "lib", "tests/e2e/data"}) copyRegularFiles(source / dir, root_ / dir);
    dropFilesNamingOutside();
    // A copy that outlives this object: a handler registered while a static is being built
    // runs after that static is destroyed.
    static const std::filesystem::path* removeAtExit = new std::filesystem::path(root_);
    std::atexit([] { std::filesystem::remove_all(*removeAtExit); });
  }

  static bool isFileKey(const std::string& key) {
    return key == "sources" || key == "mapping" || key == "extends" || key == "cell";
  }

  bool allInside(const ConfigNode& node, const std::filesystem::path& dir) const {
    if (node.kind() == ConfigNode::Kind::Scalar) return inside(node.scalar(), dir);
    for (const auto& [key, value] : node.entries())
      if (!inside(key, dir) || !allInside(value, dir)) return false;
    for (const ConfigNode& item : node.items())
      if (!allInside(item, dir)) return false;
    return true;
  }

  bool inside(const std::string& name, const std::filesystem::path& dir) const {
    if (name.find('\0') != std::string::npos) return false;
    const std::filesystem::path p = (dir / name).lexically_normal();
    auto [rootEnd, pEnd] = std::mismatch(root_.begin(), root_.end(), p.begin(), p.end());
    return rootEnd == root_.end();
  }

  static void copyRegularFiles(const std::filesystem::path& from, const std::filesystem::path& to) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(from)) {
      if (!entry.is_regular_file() || entry.is_symlink()) continue;
      const std::filesystem::path target = to / std::filesystem::relative(entry.path(), from);
      std::filesystem::create_directories(target.parent_path());
      std::filesystem::copy_file(entry.path(), target);
    }
  }

  // A YAML file of the copy is read with its paths resolved from its own folder (as a cell,
  // or a scenario's `cell:`), or from the folder of a file that `extends` it: an input loaded as
  // a cell (any copy file may be its base) or a copy file naming it. It is dropped from the copy
  // if it names a file outside from any of those folders.
  void dropFilesNamingOutside() const {
    struct File {
      std::filesystem::path path;
      ConfigNode tree;
      std::vector<std::filesystem::path> readFrom;
    };
    std::vector<File> files;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root_)) {
      if (entry.path().extension() != ".yaml") continue;
      std::ifstream in(entry.path(), std::ios::binary);
      const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      SourceManager sources;
      Diagnostics diags;
      File f{entry.path(), {}, {entry.path().parent_path()}};
      if (!cell::parseYaml(entry.path().string(), text, sources, diags, f.tree)) continue;
      for (const char* input : kLoadedAsCell) f.readFrom.push_back((root_ / input).parent_path());
      files.push_back(std::move(f));
    }
    for (const File& a : files)
      if (const ConfigNode* base = a.tree.find("extends"); base && base->kind() == ConfigNode::Kind::Scalar)
        for (File& b : files)
          if (b.path == (a.path.parent_path() / base->scalar()).lexically_normal()) b.readFrom.push_back(a.path.parent_path());
    for (const File& f : files)
      if (!std::all_of(f.readFrom.begin(), f.readFrom.end(), [&](const auto& folder) { return namesOnlyInside(f.tree, folder); }))
        std::filesystem::remove(f.path);
  }

  std::filesystem::path root_;
};

// The preamble of a file-based target: writes the input to `relative` (a k*Input path) of the
// tree and reads it there with `read(path, sources, diags)`, which gives an optional; a file it
// refuses must say why (a trap otherwise: a finding). What `read` gave.
template <class Read>
auto readInput(const char* relative, const uint8_t* data, size_t size, Read&& read) {
  const std::string path = Scratch::get().write(relative, data, size);
  SourceManager sources;
  Diagnostics diags;
  auto result = read(path, sources, diags);
  if (!result && !diags.hasErrors()) __builtin_trap();
  return result;
}

}  // namespace virtcom::fuzz
