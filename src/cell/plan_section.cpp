#include "cell/plan_section.hpp"

#include <algorithm>
#include <array>

#include "core/cell_diagnostic_codes.hpp"

namespace virtcom::cell {

namespace {

constexpr int32_t kDayMin = 24 * 60;

// "HH:MM" (00:00..23:59, or 24:00 for an end at midnight) as minutes since midnight; -1 if not.
int32_t parseTimeOfDay(const std::string& text, bool isEnd) {
  if (text.size() != 5 || text[2] != ':') return -1;
  for (size_t i : {0u, 1u, 3u, 4u})
    if (text[i] < '0' || text[i] > '9') return -1;
  int32_t h = (text[0] - '0') * 10 + (text[1] - '0'), m = (text[3] - '0') * 10 + (text[4] - '0');
  if (m > 59 || h > 24 || (h == 24 && (m != 0 || !isEnd))) return -1;
  return h * 60 + m;
}

// The shift's minutes as [start, end) with end > start (a night shift ends after 24:00).
std::pair<int32_t, int32_t> minutes(const PlannedShift& s) { return {s.startMin, s.endMin > s.startMin ? s.endMin : s.endMin + kDayMin}; }

// Two shifts overlap on the 24 h circle: compared as they are and one day shifted either way.
bool overlap(const PlannedShift& a, const PlannedShift& b) {
  auto [a0, a1] = minutes(a);
  auto [b0, b1] = minutes(b);
  return std::ranges::any_of(std::array{-kDayMin, 0, kDayMin}, [&](int32_t k) { return a0 < b1 + k && b0 + k < a1; });
}

int32_t readTime(ConfigReader& r, const ConfigNode& entry, const char* key, bool isEnd) {
  const std::string text = r.requireString(key);
  if (text.empty()) return -1;  // missing: reported by requireString
  int32_t min = parseTimeOfDay(text, isEnd);
  if (min < 0)
    r.diags().error(celldiag::C050, entry.find(key)->loc(),
                    "'" + std::string(key) + "' is '" + text + "', expected a time of day as HH:MM (e.g. \"06:00\"" +
                        (isEnd ? "; \"24:00\" for midnight)" : ")"));
  return min;
}

void readShift(Cell& cell, const ConfigNode& entry, Diagnostics& diags) {
  ConfigReader r(entry, diags, "a shift of 'plan: shifts'");
  if (!r.ok()) return;
  PlannedShift s;
  s.loc = entry.loc();
  s.name = r.requireString("name");
  s.startMin = readTime(r, entry, "start", false);
  s.endMin = readTime(r, entry, "end", true);
  const int64_t parts = r.requireInt("parts");
  if (entry.has("parts") && parts < 0)
    diags.error(celldiag::C050, entry.find("parts")->loc(), "'parts' is " + std::to_string(parts) + ", expected a count of parts (0 or more)");
  r.rejectUnknownKeys();
  if (!r.ok() || s.name.empty() || s.startMin < 0 || s.endMin < 0 || parts < 0) return;
  s.endMin %= kDayMin;  // 24:00 is the next day's 00:00
  s.parts = static_cast<uint32_t>(parts);
  for (const PlannedShift& other : cell.plan.shifts) {
    if (other.name == s.name) {
      diags.error(celldiag::C050, entry.find("name")->loc(), "a shift named '" + s.name + "' is already planned (names are unique)");
      return;
    }
    if (overlap(other, s)) {
      diags.error(celldiag::C050, s.loc, "shift '" + s.name + "' overlaps shift '" + other.name + "': a moment of the day belongs to one shift");
      return;
    }
  }
  cell.plan.shifts.push_back(std::move(s));
}

}  // namespace

void readPlanSection(Cell& cell, const ConfigNode* node, Diagnostics& diags) {
  if (!node) return;
  ConfigReader plan(*node, diags, "'plan'");
  if (!plan.ok()) return;
  const ConfigNode* shifts = plan.child("shifts");
  if (!shifts || shifts->kind() != ConfigNode::Kind::List || shifts->items().empty()) {
    diags.error(celldiag::C050, shifts ? shifts->loc() : node->loc(),
                "'plan' needs 'shifts:', a list of shifts, e.g. - { name: Early, start: \"06:00\", end: \"14:00\", parts: 400 }");
  } else {
    for (const ConfigNode& entry : shifts->items()) readShift(cell, entry, diags);
  }
  plan.rejectUnknownKeys();
}

}  // namespace virtcom::cell
