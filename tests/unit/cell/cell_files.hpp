#pragma once
// A fixture that writes a small cell (cell.yaml + ST sources) into a per-test temporary folder
// and loads it with cell::loadCell. Diagnostics are returned as the header lines a user sees
// (`cell.yaml:12:7: error[C011]: ...`) with the temporary folder stripped from the paths, so the
// expectations read exactly like the CLI output for a cell in the current folder.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "cell/cell.hpp"

namespace virtcom::cell::test {

// A PLC program with variables of every kind the wiring tests need: a handshake's worth of
// loose variables, a struct for prefix wiring, a partial struct, a CONSTANT and a TON user.
inline constexpr const char* kMainSt = R"(TYPE ST_ClampIO :
STRUCT
  programNumber : INT;
  execute : BOOL;
  done : BOOL;
  error : INT;
  busy : BOOL;
END_STRUCT
END_TYPE

TYPE ST_Partial :
STRUCT
  execute : BOOL;
  done : BOOL;
END_STRUCT
END_TYPE

PROGRAM MAIN
VAR
  cmd : INT;
  exec : BOOL;
  done : BOOL;
  err : INT;
  busy : BOOL;
  level : LREAL;
  finished : BOOL;
  count : INT;
  Clamp : ST_ClampIO;
  Part : ST_Partial;
  Other : ST_Partial;
END_VAR
VAR CONSTANT
  kLocked : BOOL := FALSE;
END_VAR
count := count + 1;
END_PROGRAM
)";

// One `timed` device entry body (indented for a list item under `devices:`).
inline constexpr const char* kClampParams = R"(    commands:
      1: { name: Close, duration: 1 s }
)";

class CellFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::path(::testing::TempDir()) /
           ("virtcom_cell_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
            std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }

  void write(const std::string& name, const std::string& text) {
    std::ofstream out(dir_ / name, std::ios::binary);
    out << text;
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // Loads dir/<name> into fresh diagnostics.
  std::unique_ptr<Cell> load(const std::string& name = "cell.yaml") {
    sources_ = SourceManager();
    diags_ = Diagnostics();
    return loadCell(path(name), sources_, diags_);
  }

  // Writes `text` as cell.yaml and loads it; the load must succeed.
  std::unique_ptr<Cell> loads(const std::string& text) {
    write("cell.yaml", text);
    auto cell = load();
    EXPECT_TRUE(cell != nullptr) << rendered();
    return cell;
  }
  // Writes `text` as cell.yaml and loads it; the load must fail. Its errors (see errors()).
  std::vector<std::string> fails(const std::string& text) {
    write("cell.yaml", text);
    EXPECT_TRUE(load() == nullptr) << "the broken cell loaded";
    return errors();
  }

  // `file:line:col: error[CODE]: message` per diagnostic, in report order, folder stripped.
  std::vector<std::string> errors() const {
    std::vector<std::string> out;
    for (const auto& d : diags_.all()) {
      std::string text = renderDiagnostic(d, sources_);
      text = text.substr(0, text.find('\n'));
      out.push_back(stripDir(text));
    }
    return out;
  }
  // The whole rendering (with quoted lines and carets), folder stripped.
  std::string rendered() const { return stripDir(diags_.render(sources_)); }

  std::string stripDir(std::string text) const {
    const std::string prefix = dir_.string() + "/";
    for (size_t at = text.find(prefix); at != std::string::npos; at = text.find(prefix, at))
      text.erase(at, prefix.size());
    return text;
  }

  std::filesystem::path dir_;
  SourceManager sources_;
  Diagnostics diags_;
};

}  // namespace virtcom::cell::test
