// The Gantt chart of the HTML report: one lane per device, bars per activity (seed Figure 11).
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "report/html_chart.hpp"
#include "report/text_util.hpp"

namespace virtcom::report::html {

namespace {

constexpr double kTopPadPx = 6;
constexpr double kCycleRowPx = 24;
constexpr double kEventRowPx = 17;
constexpr int kMaxEventRows = 3;
constexpr size_t kMaxEventLabels = 60;  // beyond this only lines and tooltips
constexpr double kGroupHeaderPx = 22;
constexpr double kLanePadPx = 5;     // above and below the bars of a lane
constexpr double kBarPx = 20;        // one track; overlapping activities stack in tracks
constexpr double kTrackGapPx = 2;
constexpr int kMaxTracks = 4;        // more overlap than this shares tracks
constexpr double kMinLabelBarPx = 14;
constexpr double kMinBarPx = 2;     // narrower bars are merged with their neighbours
constexpr double kMergeGapPx = 1;
constexpr size_t kLaneNameChars = 24;

std::string px(double v) { return formatFixed(v, 1); }

struct Group {
  std::string name;
  std::vector<uint32_t> devices;
};

// Robots, Press, Axes, then custom groups in order of appearance, then Other.
std::vector<Group> groupDevices(const Trace& trace) {
  static const std::vector<std::string> kFixed = {"Robots", "Press", "Axes"};
  std::vector<Group> groups;
  for (uint32_t i = 0; i < trace.devices.size(); ++i) {
    std::string name = laneGroup(trace.devices[i]);
    auto it = std::find_if(groups.begin(), groups.end(), [&](const Group& g) { return g.name == name; });
    if (it == groups.end()) {
      groups.push_back({name, {}});
      it = groups.end() - 1;
    }
    it->devices.push_back(i);
  }
  auto rank = [&](const Group& g) {
    auto f = std::find(kFixed.begin(), kFixed.end(), g.name);
    if (f != kFixed.end()) return static_cast<int>(f - kFixed.begin());
    return g.name == "Other" ? 4 : 3;
  };
  std::stable_sort(groups.begin(), groups.end(),
                   [&](const Group& a, const Group& b) { return rank(a) < rank(b); });
  return groups;
}

struct Event {
  double x = 0;
  bool collision = true;
  std::string text;   // label above the chart (raw, escaped when written)
  std::string title;  // tooltip
  int row = -1;       // -1: no label
  bool anchorEnd = false;
};

std::vector<Event> collectEvents(const Trace& trace, const TimeScale& s) {
  std::vector<Event> events;
  for (const CollisionRecord& c : trace.collisions) {
    if (!s.contains(c.timeNs)) continue;
    Event e;
    e.x = s.x(c.timeNs);
    e.text = "Collision " + labelName(trace, c.zone) + ": " + deviceName(trace, c.deviceA) +
             " \u2194 " + deviceName(trace, c.deviceB);
    e.title = "Collision at " + formatSeconds(c.timeNs, 3) + " s in zone " + labelName(trace, c.zone) +
              "\n" + deviceName(trace, c.deviceA) + " (" + labelName(trace, c.activityA) + ") \u2194 " +
              deviceName(trace, c.deviceB) + " (" + labelName(trace, c.activityB) + ")";
    events.push_back(std::move(e));
  }
  for (const FaultRecord& f : trace.faults) {
    if (!s.contains(f.timeNs)) continue;
    Event e;
    e.x = s.x(f.timeNs);
    e.collision = false;
    e.text = "Fault: " + f.source;
    e.title = "Fault at " + formatSeconds(f.timeNs, 3) + " s from " + f.source + "\n" + f.message;
    events.push_back(std::move(e));
  }
  std::stable_sort(events.begin(), events.end(), [](const Event& a, const Event& b) { return a.x < b.x; });
  return events;
}

// Greedy rows for the event labels: first row where the label does not overlap the previous
// one; labels that fit nowhere get no text (their tooltip still tells all). Returns the rows used.
int placeEventLabels(std::vector<Event>& events, const TimeScale& s) {
  if (events.size() > kMaxEventLabels) return 0;
  double rowEnd[kMaxEventRows];
  std::fill(std::begin(rowEnd), std::end(rowEnd), -1e9);
  int rows = 0;
  for (Event& e : events) {
    double w = static_cast<double>(displayWidth(e.text)) * kCharPx;
    double left = e.x + 4;
    if (left + w > s.widthPx - 4) {
      e.anchorEnd = true;
      left = e.x - 4 - w;
    }
    for (int r = 0; r < kMaxEventRows; ++r) {
      if (rowEnd[r] + 8 < left) {
        e.row = r;
        rowEnd[r] = left + w;
        rows = std::max(rows, r + 1);
        break;
      }
    }
  }
  return rows;
}

struct Segment {
  double x0 = 0, x1 = 0;
  uint32_t label = 0;
  uint32_t device = 0;
  bool mixed = false, error = false, running = false;
  size_t count = 0;
  int64_t startNs = 0, endNs = 0;
  double energyJ = 0;
  int32_t errorCode = 0;
};

std::string segmentSvg(const Trace& trace, const Segment& g, double y, double height, const LabelColors& colors) {
  Rgb fill = colors.color(g.label);
  std::string fillHex = g.mixed ? kMergedColor : hex(fill);
  double width = std::max(g.x1 - g.x0, 1.0);
  std::string cls = g.error ? "bar err" : g.running ? "bar run" : "bar";
  std::string title = sanitizeUtf8(deviceName(trace, g.device)) + " \u00b7 ";
  if (g.count > 1)
    title += std::to_string(g.count) + " operations (merged at this zoom)" +
             (g.mixed ? std::string() : " of " + labelName(trace, g.label));
  else
    title += labelName(trace, g.label);
  title += "\n" + formatSeconds(g.startNs, 3) + " s \u2192 " + formatSeconds(g.endNs, 3) + " s (" +
           formatSeconds(g.endNs - g.startNs, 3) + " s)\nenergy " + formatFixed(g.energyJ, 1) + " J";
  if (g.error) title += g.count > 1 ? "\nincludes an error" : "\nerror code " + std::to_string(g.errorCode);
  if (g.running) title += "\nstill running when the run ended";
  std::string out = "<rect class=\"" + cls + "\" x=\"" + px(g.x0) + "\" y=\"" + px(y) + "\" width=\"" +
                    px(width) + "\" height=\"" + px(height) + "\" fill=\"" + fillHex + "\"><title>" +
                    escapeHtml(title) + "</title></rect>";
  if (g.count == 1) {
    const std::string& label = labelName(trace, g.label);
    double textW = static_cast<double>(displayWidth(label)) * kCharPx;
    if (width >= textW + 8 && height >= kMinLabelBarPx)
      out += "<text class=\"bar-label\" x=\"" + px(g.x0 + 4) + "\" y=\"" + px(y + height / 2 + 4) +
             "\" fill=\"" + textColorOn(fill) + "\">" + escapeHtml(label) + "</text>";
  }
  return out;
}

Segment startSegment(const Trace& trace, const ActivityRecord& a, const TimeScale& s) {
  Segment g;
  g.startNs = a.startNs;
  g.endNs = activityEndNs(trace, a);
  g.x0 = s.clampedX(g.startNs);
  g.x1 = s.clampedX(g.endNs);
  g.label = a.label;
  g.device = a.device;
  g.error = a.errorCode != 0;
  g.errorCode = a.errorCode;
  g.running = a.endNs < 0;
  g.count = 1;
  g.energyJ = a.energyJ;
  return g;
}

// Bars of one lane; sub-pixel neighbours merged so the SVG stays small for long runs.
std::string trackBars(const Trace& trace, const std::vector<uint32_t>& activities, double y, double height,
                      const TimeScale& s, const LabelColors& colors) {
  std::string out;
  Segment pending;
  bool hasPending = false;
  auto flush = [&] {
    if (hasPending) out += segmentSvg(trace, pending, y, height, colors);
    hasPending = false;
  };
  for (uint32_t idx : activities) {
    Segment g = startSegment(trace, trace.activities[idx], s);
    if (g.x1 - g.x0 >= kMinBarPx) {
      flush();
      out += segmentSvg(trace, g, y, height, colors);
    } else if (hasPending && g.x0 - pending.x1 <= kMergeGapPx) {
      pending.x1 = std::max(pending.x1, g.x1);
      pending.endNs = std::max(pending.endNs, g.endNs);
      pending.mixed |= g.label != pending.label;
      pending.error |= g.error;
      pending.running |= g.running;
      pending.energyJ += g.energyJ;
      ++pending.count;
    } else {
      flush();
      pending = g;
      hasPending = true;
    }
  }
  flush();
  return out;
}

// Where each activity of a lane goes: activities that overlap in time form a cluster whose
// members stack in tracks (greedy, first free track); a cluster of one fills the lane height.
struct Placement {
  uint32_t activity;
  int track, tracks;
};

struct LanePlan {
  std::vector<Placement> placements;
  int maxTracks = 1;
  double heightPx() const { return 2 * kLanePadPx + maxTracks * kBarPx + (maxTracks - 1) * kTrackGapPx; }
};

LanePlan planLane(const Trace& trace, std::vector<uint32_t> activities) {
  auto start = [&](uint32_t i) { return trace.activities[i].startNs; };
  auto end = [&](uint32_t i) { return activityEndNs(trace, trace.activities[i]); };
  std::stable_sort(activities.begin(), activities.end(), [&](uint32_t a, uint32_t b) { return start(a) < start(b); });
  LanePlan plan;
  for (size_t i = 0; i < activities.size();) {
    size_t j = i + 1;
    int64_t clusterEnd = end(activities[i]);
    for (; j < activities.size() && start(activities[j]) < clusterEnd; ++j)
      clusterEnd = std::max(clusterEnd, end(activities[j]));
    std::vector<int64_t> trackEnds;
    std::vector<int> track(j - i);
    for (size_t k = i; k < j; ++k) {
      size_t t = 0;
      while (t < trackEnds.size() && trackEnds[t] > start(activities[k])) ++t;
      if (t == trackEnds.size()) trackEnds.push_back(0);
      trackEnds[t] = end(activities[k]);
      track[k - i] = static_cast<int>(t);
    }
    int tracks = std::min(static_cast<int>(trackEnds.size()), kMaxTracks);
    plan.maxTracks = std::max(plan.maxTracks, tracks);
    for (size_t k = i; k < j; ++k) plan.placements.push_back({activities[k], track[k - i] % tracks, tracks});
    i = j;
  }
  return plan;
}

// All bars of a lane whose top is at `laneTop`; merging happens per track.
std::string laneBars(const Trace& trace, const LanePlan& plan, double laneTop, const TimeScale& s,
                     const LabelColors& colors) {
  std::map<std::pair<int, int>, std::vector<uint32_t>> byTrack;  // (tracks, track) -> activities
  for (const Placement& p : plan.placements) byTrack[{p.tracks, p.track}].push_back(p.activity);
  double inner = plan.heightPx() - 2 * kLanePadPx;
  std::string out;
  for (const auto& [key, activities] : byTrack) {
    auto [tracks, track] = key;
    double band = (inner - (tracks - 1) * kTrackGapPx) / tracks;
    out += trackBars(trace, activities, laneTop + kLanePadPx + track * (band + kTrackGapPx), band, s, colors);
  }
  return out;
}

std::string cycleBracket(const Kpis& kpis, const TimeScale& s, double y) {
  double x0 = s.x(kpis.windowStartNs), x1 = s.x(kpis.windowEndNs);
  std::string text = "Cycle time " + formatSeconds(kpis.cycleTimeNs, 3) + " s";
  // The label is bold: wider than kCharPx per character (issue 16: its end was clipped).
  constexpr double kBoldCharPx = 7.2;
  const double textW = static_cast<double>(text.size()) * kBoldCharPx;
  const double w = textW + 12;
  double line = y + 17;
  std::string out = "<g class=\"cycle-bracket\"><line x1=\"" + px(x0) + "\" x2=\"" + px(x1) + "\" y1=\"" +
                    px(line) + "\" y2=\"" + px(line) + "\"/><line x1=\"" + px(x0) + "\" x2=\"" + px(x0) +
                    "\" y1=\"" + px(line - 5) + "\" y2=\"" + px(line + 5) + "\"/><line x1=\"" + px(x1) +
                    "\" x2=\"" + px(x1) + "\" y1=\"" + px(line - 5) + "\" y2=\"" + px(line + 5) + "\"/>";
  if (x1 - x0 >= w)
    out += "<rect x=\"" + px((x0 + x1 - w) / 2) + "\" y=\"" + px(line - 8) + "\" width=\"" + px(w) +
           "\" height=\"16\" rx=\"3\"/><text x=\"" + px((x0 + x1) / 2) + "\" y=\"" + px(line + 4) +
           "\" text-anchor=\"middle\">" + text + "</text>";
  else if (x1 + 6 + textW <= s.widthPx)  // beside the bracket, right
    out += "<text x=\"" + px(x1 + 6) + "\" y=\"" + px(line + 4) + "\">" + text + "</text>";
  else  // a short last cycle at the right edge: left of the bracket, inside the chart
    out += "<text x=\"" + px(std::max(x0 - 6, textW)) + "\" y=\"" + px(line + 4) + "\" text-anchor=\"end\">" + text +
           "</text>";
  return out + "</g>\n";
}

// A long run's elided activities (docs/report.md "Long runs"): their span is hatched and says how
// many bars it stands for, so an empty stretch is never read as idle devices.
std::string elidedSpan(const Trace& trace, const TimeScale& s, double top, double bottom) {
  const ActivityLog& log = trace.activities;
  if (log.elidedCount() == 0 || !s.overlaps(log.elidedFromNs(), log.elidedToNs())) return {};
  const double x0 = s.clampedX(log.elidedFromNs()), x1 = s.clampedX(log.elidedToNs());
  return "<g class=\"elided\"><rect x=\"" + px(x0) + "\" y=\"" + px(top) + "\" width=\"" + px(std::max(x1 - x0, 1.0)) +
         "\" height=\"" + px(bottom - top) + "\" fill=\"#8882\"/><text x=\"" + px(x0 + 4) + "\" y=\"" + px(top + 12) +
         "\" font-size=\"11\">" + std::to_string(log.elidedCount()) + " activities elided, " +
         formatSeconds(log.elidedFromNs(), 3) + " s \u2013 " + formatSeconds(log.elidedToNs(), 3) + " s</text></g>\n";
}

}  // namespace

std::string ganttSvg(const Trace& trace, const Kpis& kpis, const TimeScale& s, const LabelColors& colors) {
  std::vector<Group> groups = groupDevices(trace);
  std::vector<Event> events = collectEvents(trace, s);
  int eventRows = placeEventLabels(events, s);

  double y = kTopPadPx;
  double cycleY = y;
  if (kpis.cycleMeasured) y += kCycleRowPx;
  double eventsY = y;
  y += eventRows * kEventRowPx + 4;
  const double lanesTop = y;

  std::vector<std::vector<uint32_t>> byDevice(trace.devices.size());
  for (uint32_t i : heldActivities(trace))
    if (trace.activities[i].device < byDevice.size() &&
        s.overlaps(trace.activities[i].startNs, activityEndNs(trace, trace.activities[i])))
      byDevice[trace.activities[i].device].push_back(i);
  std::vector<LanePlan> plans;
  for (const auto& activities : byDevice) plans.push_back(planLane(trace, activities));

  // Lane positions first: markers need them.
  std::vector<double> laneY(trace.devices.size(), -1);
  std::vector<double> groupY;
  for (const Group& g : groups) {
    groupY.push_back(y);
    y += kGroupHeaderPx;
    for (uint32_t d : g.devices) {
      laneY[d] = y;
      y += plans[d].heightPx();
    }
  }
  if (groups.empty()) y += 30;
  const double lanesBottom = y;
  const double height = lanesBottom + 40;

  std::string out = "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"chart gantt\" viewBox=\"0 0 " +
                    px(s.widthPx) + " " + px(height) + "\" width=\"" + px(s.widthPx) + "\" height=\"" +
                    px(height) + "\" role=\"img\" aria-label=\"Gantt chart of device activities\">\n";
  // Lane backgrounds (zebra) and group headers.
  size_t laneNo = 0;
  for (size_t gi = 0; gi < groups.size(); ++gi) {
    out += "<line class=\"group-rule\" x1=\"0\" x2=\"" + px(s.widthPx) + "\" y1=\"" + px(groupY[gi]) +
           "\" y2=\"" + px(groupY[gi]) + "\"/><text class=\"group\" x=\"8\" y=\"" + px(groupY[gi] + 15) +
           "\">" + escapeHtml(groups[gi].name) + "</text>\n";
    for (uint32_t d : groups[gi].devices)
      if (laneNo++ % 2 == 1)
        out += "<rect class=\"zebra\" x=\"0\" y=\"" + px(laneY[d]) + "\" width=\"" + px(s.widthPx) +
               "\" height=\"" + px(plans[d].heightPx()) + "\"/>";
  }
  out += cycleShade(s, kpis, lanesTop, lanesBottom);
  out += elidedSpan(trace, s, lanesTop, lanesBottom);
  out += timeGrid(s, lanesTop, lanesBottom);
  if (groups.empty())
    out += "<text class=\"empty\" x=\"" + px(s.leftPx + 8) + "\" y=\"" + px(lanesTop + 19) +
           "\">no devices in this trace</text>";

  for (const Group& g : groups)
    for (uint32_t d : g.devices) {
      const DeviceInfo& info = trace.devices[d];
      out += "<text class=\"lane\" x=\"16\" y=\"" + px(laneY[d] + plans[d].heightPx() / 2 + 4) + "\">" +
             escapeHtml(fitWidth(info.name, kLaneNameChars, "\u2026")) + "<title>" +
             escapeHtml(info.name + " (" + info.type + ")") + "</title></text>";
      out += "<g class=\"bars\">" + laneBars(trace, plans[d], laneY[d], s, colors) + "</g>\n";
    }

  if (kpis.cycleMeasured) out += cycleBracket(kpis, s, cycleY);
  // Events: vertical line over the lanes, markers on the lanes involved, label above the chart.
  std::set<std::pair<bool, long>> drawn;
  for (const Event& e : events) {
    const char* cls = e.collision ? "collision" : "fault";
    std::string x = px(e.x);
    std::string title = "<title>" + escapeHtml(e.title) + "</title>";
    if (drawn.insert({e.collision, std::lround(e.x * 2)}).second || e.row >= 0)
      out += "<line class=\"" + std::string(cls) + "\" x1=\"" + x + "\" x2=\"" + x + "\" y1=\"" +
             px(eventsY) + "\" y2=\"" + px(lanesBottom) + "\">" + title + "</line>";
    if (e.row >= 0)
      out += "<text class=\"" + std::string(cls) + "-label\" x=\"" + px(e.anchorEnd ? e.x - 4 : e.x + 4) +
             "\" y=\"" + px(eventsY + e.row * kEventRowPx + 12) + "\"" +
             (e.anchorEnd ? " text-anchor=\"end\"" : "") + ">" + escapeHtml(e.text) + title + "</text>";
  }
  for (const CollisionRecord& c : trace.collisions)
    for (uint32_t d : {c.deviceA, c.deviceB})
      if (d < laneY.size() && s.contains(c.timeNs))
        out += "<circle class=\"collision-dot\" cx=\"" + px(s.x(c.timeNs)) + "\" cy=\"" +
               px(laneY[d] + plans[d].heightPx() / 2) + "\" r=\"5\"/>";
  for (const FaultRecord& f : trace.faults)
    for (uint32_t d = 0; d < trace.devices.size(); ++d)
      if (trace.devices[d].name == f.source && s.contains(f.timeNs)) {
        double cx = s.x(f.timeNs), cy = laneY[d] + plans[d].heightPx() / 2;
        out += "<path class=\"fault-dot\" d=\"M" + px(cx) + " " + px(cy - 6) + "L" + px(cx + 6) + " " +
               px(cy) + "L" + px(cx) + " " + px(cy + 6) + "L" + px(cx - 6) + " " + px(cy) + "Z\"/>";
      }

  out += timeAxis(s, lanesBottom);
  return out + "</svg>\n";
}

}  // namespace virtcom::report::html
