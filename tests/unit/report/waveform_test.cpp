#include <gtest/gtest.h>

#include <map>
#include <sstream>

#include "report/waveform.hpp"
#include "example_trace.hpp"

namespace virtcom::report {
namespace {

std::vector<std::string> lines(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

struct ParsedVcd {
  std::map<std::string, std::string> idOf;     // "scope.name" -> id
  std::map<std::string, std::string> declOf;   // "scope.name" -> "$var ... $end"
  // Value of each id at each timestamp where it changed, dumpvars at 0.
  std::map<std::string, std::map<int64_t, std::string>> values;
  std::vector<int64_t> timestamps;
};

// A minimal reader for what vcdReport writes (one declaration or value per line).
ParsedVcd parseVcd(const std::string& text) {
  ParsedVcd p;
  std::vector<std::string> scopes;
  int64_t now = 0;
  bool body = false;
  for (const std::string& line : lines(text)) {
    std::istringstream in(line);
    std::string tok;
    in >> tok;
    if (tok == "$scope") {
      std::string kind, name;
      in >> kind >> name;
      scopes.push_back(name);
    } else if (tok == "$upscope") {
      scopes.pop_back();
    } else if (tok == "$var") {
      std::string type, width, id, ref;
      in >> type >> width >> id >> ref;
      std::string path;
      for (const auto& s : scopes) path += s + ".";
      p.idOf[path + ref] = id;
      p.declOf[path + ref] = line;
    } else if (tok == "$enddefinitions") {
      body = true;
    } else if (body && tok.starts_with("#")) {
      now = std::stoll(tok.substr(1));
      p.timestamps.push_back(now);
    } else if (body && (tok.starts_with("b") || tok.starts_with("r"))) {
      std::string id;
      in >> id;
      p.values[id][now] = tok;
    } else if (body && (tok[0] == '0' || tok[0] == '1')) {
      p.values[tok.substr(1)][now] = tok.substr(0, 1);
    }
  }
  return p;
}

// The value an id holds at time t (last change at or before t).
std::string valueAt(const ParsedVcd& p, const std::string& path, int64_t t) {
  const auto& changes = p.values.at(p.idOf.at(path));
  auto it = changes.upper_bound(t);
  return it == changes.begin() ? "?" : std::prev(it)->second;
}

TEST(Vcd, Header) {
  std::string vcd = vcdReport(testing::exampleCellTrace());
  auto l = lines(vcd);
  ASSERT_GE(l.size(), 3u);
  EXPECT_EQ(l[0], "$version virtcom $end");
  EXPECT_EQ(l[1], "$timescale 1 ns $end");
  EXPECT_EQ(l[2], "$comment not dumped (STRING/WSTRING): Cell.recipe $end");
  EXPECT_NE(vcd.find("$enddefinitions $end\n#0\n$dumpvars\n"), std::string::npos);
  EXPECT_TRUE(vcd.ends_with("#75000000000\n"));
  EXPECT_EQ(vcd.find("$date"), std::string::npos);  // deterministic
}

TEST(Vcd, ScopesPerDevicePrefixAndVarTypes) {
  ParsedVcd p = parseVcd(vcdReport(testing::exampleCellTrace()));
  EXPECT_EQ(p.declOf.at("virtcom.PLC.start"), "$var wire 1 ! start $end");
  EXPECT_EQ(p.declOf.at("virtcom.Robot1.busy"), "$var wire 1 \" busy $end");
  EXPECT_EQ(p.declOf.at("virtcom.Press.force"), "$var real 64 # force $end");
  EXPECT_EQ(p.declOf.at("virtcom.Robot2.error"), "$var integer 32 $ error $end");
  EXPECT_EQ(p.declOf.at("virtcom.TableX.pos"), "$var real 64 % pos $end");
  EXPECT_EQ(p.declOf.at("virtcom.Robot1.torque"), "$var integer 16 & torque $end");
  EXPECT_EQ(p.declOf.at("virtcom.cycle_count"), "$var wire 32 ' cycle_count $end");
  EXPECT_EQ(p.declOf.size(), 7u);
}

TEST(Vcd, ValuesAtGivenTimes) {
  ParsedVcd p = parseVcd(vcdReport(testing::exampleCellTrace()));
  using testing::kS;
  EXPECT_EQ(valueAt(p, "virtcom.PLC.start", 0), "0");
  EXPECT_EQ(valueAt(p, "virtcom.PLC.start", 2 * kS), "1");
  EXPECT_EQ(valueAt(p, "virtcom.PLC.start", 3 * kS), "0");
  EXPECT_EQ(valueAt(p, "virtcom.Robot1.busy", 0), "1");
  EXPECT_EQ(valueAt(p, "virtcom.Robot1.busy", 13 * kS), "0");
  EXPECT_EQ(valueAt(p, "virtcom.Press.force", 11 * kS), "r1000.5");
  EXPECT_EQ(valueAt(p, "virtcom.Press.force", 12 * kS), "r3500.25");
  EXPECT_EQ(valueAt(p, "virtcom.Press.force", 20 * kS), "r0");
  EXPECT_EQ(valueAt(p, "virtcom.Robot2.error", 38 * kS), "b10001");
  EXPECT_EQ(valueAt(p, "virtcom.Robot2.error", 39 * kS), "b10001");
  EXPECT_EQ(valueAt(p, "virtcom.Robot2.error", 40 * kS), "b0");
  EXPECT_EQ(valueAt(p, "virtcom.Robot1.torque", 20 * kS), "b1111111111111011");  // -5, full width
  EXPECT_EQ(valueAt(p, "virtcom.cycle_count", 74 * kS), "b1");
  // Timestamps strictly increase.
  for (size_t i = 1; i < p.timestamps.size(); ++i) EXPECT_LT(p.timestamps[i - 1], p.timestamps[i]);
}

TEST(Vcd, SanitisesNamesAndSkipsBadChanges) {
  Trace t;
  t.signals.push_back({"Dev 1.my signal", ElemType::Bool, 0});
  t.changes.push_back({5, 0, 1});
  t.changes.push_back({6, 9, 1});  // unknown tag
  t.endNs = 10;
  std::string vcd = vcdReport(t);
  EXPECT_NE(vcd.find("$scope module Dev_1 $end\n$var wire 1 ! my_signal $end\n$upscope $end\n"), std::string::npos)
      << vcd;
  EXPECT_NE(vcd.find("#5\n1!\n#10\n"), std::string::npos) << vcd;
}

TEST(Csv, HeaderInitialValuesThenChanges) {
  auto l = lines(csvChanges(testing::exampleCellTrace()));
  ASSERT_GE(l.size(), 9u);
  EXPECT_EQ(l[0], "time_s,signal,value");
  EXPECT_EQ(l[1], "0.000000000,PLC.start,0");
  EXPECT_EQ(l[2], "0.000000000,Robot1.busy,1");
  EXPECT_EQ(l[3], "0.000000000,Press.force,0");
  EXPECT_EQ(l[7], "0.000000000,cycle_count,0");
  EXPECT_EQ(l[8], "2.000000000,PLC.start,1");   // Cell.recipe (STRING) has no rows
  EXPECT_EQ(l[9], "2.500000000,PLC.start,0");
  EXPECT_EQ(l[10], "4.000000000,TableX.pos,120.5");
  EXPECT_EQ(l[13], "12.000000000,Press.force,3500.25");
  EXPECT_EQ(l[15], "14.000000000,Robot1.torque,-5");
  EXPECT_EQ(l.back(), "73.000000000,cycle_count,1");
  EXPECT_EQ(l.size(), 1u + 7u + 20u);
}

TEST(Csv, QuotesNamesAndKeepsNanosecondPrecision) {
  Trace t;
  t.signals.push_back({"a,\"b\"", ElemType::Uint, 0});
  t.changes.push_back({1'234'567'891, 0, 65535});
  std::string csv = csvChanges(t);
  EXPECT_EQ(csv, "time_s,signal,value\n0.000000000,\"a,\"\"b\"\"\",0\n1.234567891,\"a,\"\"b\"\"\",65535\n");
}

}  // namespace
}  // namespace virtcom::report
