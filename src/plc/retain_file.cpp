#include "plc/retain_file.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/atomic_file.hpp"

namespace virtcom::plc {

std::vector<RetainedVariable> retainedVariables(const bc::Module& m) {
  std::vector<RetainedVariable> out;
  for (const bc::Symbol& s : m.symbols)
    if (s.retain && s.bit < 0) out.push_back({s.name, s.type, s.address});  // located bits: the I/O image's
  for (const bc::ProgramInstance& p : m.programs) {
    if (p.pou >= m.pous.size() || m.pous[p.pou].instanceType >= m.types.size()) continue;
    for (const bc::Field& f : m.types[m.pous[p.pou].instanceType].fields)
      if (f.retain && !f.absolute) out.push_back({p.name + "." + f.name, f.type, p.address + f.offset});
  }
  return out;
}

static std::string toHex(const uint8_t* p, size_t n) {
  static const char* const kDigits = "0123456789abcdef";
  std::string s;
  for (size_t i = 0; i < n; ++i) {
    s += kDigits[p[i] >> 4];
    s += kDigits[p[i] & 15];
  }
  return s;
}

static bool fromHex(const std::string& s, std::vector<uint8_t>& out) {
  auto digit = [](char c) { return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1; };
  if (s.size() % 2) return false;
  out.clear();
  for (size_t i = 0; i < s.size(); i += 2) {
    int hi = digit(s[i]), lo = digit(s[i + 1]);
    if (hi < 0 || lo < 0) return false;
    out.push_back(static_cast<uint8_t>(hi * 16 + lo));
  }
  return true;
}

std::string loadRetainFile(const std::string& path, const bc::Module& m, uint8_t* memory, size_t& restored) {
  restored = 0;
  std::ifstream in(path);
  if (!in) return std::filesystem::exists(path) ? "cannot read " + path : std::string();
  return loadRetainText(in, path, m, memory, restored);
}

std::string loadRetainText(std::istream& in, const std::string& path, const bc::Module& m, uint8_t* memory, size_t& restored) {
  restored = 0;
  std::map<std::string, const RetainedVariable*> byName;
  const std::vector<RetainedVariable> vars = retainedVariables(m);
  for (const auto& v : vars) byName[v.name] = &v;
  std::string line;
  std::vector<uint8_t> bytes;
  for (int lineNo = 1; std::getline(in, line); ++lineNo) {
    std::istringstream fields(line);
    std::string name, hex, type;
    fields >> name >> hex;
    std::getline(fields >> std::ws, type);
    if (name.empty()) continue;
    if (type.empty() || !fromHex(hex, bytes))
      return path + ":" + std::to_string(lineNo) + ": expected NAME HEX TYPE";
    auto it = byName.find(name);
    if (it == byName.end()) continue;
    const bc::TypeDesc& t = m.types[it->second->type];
    if (t.name != type || t.size != bytes.size()) continue;
    std::copy(bytes.begin(), bytes.end(), memory + it->second->address);
    ++restored;
  }
  return {};
}

std::string saveRetainFile(const std::string& path, const bc::Module& m, const uint8_t* memory) {
  std::ostringstream out;
  for (const auto& v : retainedVariables(m)) {
    const bc::TypeDesc& t = m.types[v.type];
    out << v.name << ' ' << toHex(memory + v.address, t.size) << ' ' << t.name << '\n';
  }
  // Never half a file, whenever the process dies (core/atomic_file.hpp).
  if (std::string why = replaceFile(path, out.str()); !why.empty()) return "cannot write " + path + ": " + why;
  return {};
}

}  // namespace virtcom::plc
