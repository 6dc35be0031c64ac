#pragma once
// A hand-built Trace of a gearbox assembly cell (seed Figure 11: table axes, press, two robots),
// shared by the report tests and the render example. Every number is chosen so the KPIs can be
// computed by hand; see the comments for the expected values.
#include <bit>
#include <string>

#include "core/trace.hpp"

namespace virtcom::report::testing {

inline constexpr int64_t kS = 1'000'000'000;  // ns per second

inline void activity(Trace& t, uint32_t device, const std::string& label, double startS, double endS,
                     double energyJ, int32_t error = 0) {
  uint32_t a = t.beginActivity(device, t.internLabel(label), static_cast<int64_t>(startS * kS));
  if (endS >= 0) t.endActivity(a, static_cast<int64_t>(endS * kS), energyJ, error);
}

inline TagId signal(Trace& t, const std::string& name, ElemType type, uint64_t initial = 0) {
  t.signals.push_back({name, type, initial});
  return static_cast<TagId>(t.signals.size() - 1);
}

inline uint64_t realRaw(double v) { return std::bit_cast<uint64_t>(v); }

// Measured cycle 2 s .. 73 s (71 s), run end 75 s.
//   Robot1  busy 46 s: [2,12] (PickBearing clipped at 2) + [14,35] (two ScrewStud overlapping)
//                      + [40,52] + [70,73] (UnlockInsert clipped at 73); 6 operations
//   Robot2  busy 38 s: 6 + 11 + 5 (error 17) + 15 + 1 (PlaceBearing still running, clipped);
//                      5 operations, 1 error, 1 running
//   Press   busy 19 s; TableX 5 s (3rd move after the window); TableY 4 s;
//   Feeder  5 s (its first feed ends exactly at the window start and does not count)
// Totals: 4871.2 + 12196.1 + 5600 + 130.5 + 90.25 + 75 = 22963.05 J.
// One collision at 29 s, one fault at 38 s.
inline Trace exampleCellTrace() {
  Trace t;
  uint32_t r1 = t.addDevice("Robot1", "robot");
  uint32_t r2 = t.addDevice("Robot2", "robot");
  uint32_t press = t.addDevice("Press", "press");
  uint32_t tx = t.addDevice("TableX", "axis");
  uint32_t ty = t.addDevice("TableY", "axis");
  uint32_t feeder = t.addDevice("Feeder", "conveyor");
  uint32_t zone = t.internLabel("SharedZone");

  activity(t, feeder, "Feed", 0, 2, 15);
  activity(t, r1, "PickBearing", 0, 5, 300);
  activity(t, tx, "MoveX", 1, 4, 50);
  activity(t, r2, "PickBearing", 3, 9, 420);
  activity(t, ty, "MoveY", 4, 6, 20);
  activity(t, r1, "PlaceBearing", 5, 12, 650);
  activity(t, press, "PressFit", 10, 18, 2500);
  activity(t, r1, "ScrewStud", 14, 30, 1400);
  activity(t, r2, "PlaceBearing", 20, 31, 800);
  activity(t, r1, "ScrewStud", 28, 35, 500);
  activity(t, r2, "PickBearing", 33, 38, 210, 17);
  activity(t, tx, "MoveX", 36, 39, 40);
  activity(t, ty, "MoveY", 39, 41, 25);
  activity(t, r1, "LockInsert", 40, 52, 900);
  activity(t, r2, "ScrewStud", 45, 60, 1200);
  activity(t, press, "PressFit", 55, 66, 3100);
  activity(t, feeder, "Feed", 60, 65, 30);
  activity(t, r1, "UnlockInsert", 70, 75, 400);
  activity(t, r2, "PlaceBearing", 72, -1, 0);
  activity(t, tx, "MoveX", 74, 75, 10);

  t.collisions.push_back({29 * kS, zone, r1, r2, t.internLabel("ScrewStud"), t.internLabel("PlaceBearing")});
  t.faults.push_back({38 * kS, "Robot2", "gripper lost the bearing (error 17)"});

  double energy[] = {4871.2, 12196.1, 5600.0, 130.5, 90.25, 75.0};
  int64_t busy[] = {49 * kS, 40 * kS, 19 * kS, 7 * kS, 4 * kS, 7 * kS};
  for (uint32_t d = 0; d < 6; ++d) t.totals[d] = {busy[d], energy[d]};

  TagId start = signal(t, "PLC.start", ElemType::Bool);
  TagId r1busy = signal(t, "Robot1.busy", ElemType::Bool, 1);
  TagId force = signal(t, "Press.force", ElemType::Lreal, realRaw(0.0));
  TagId err = signal(t, "Robot2.error", ElemType::Dint);
  TagId pos = signal(t, "TableX.pos", ElemType::Real, realRaw(0.0));
  TagId torque = signal(t, "Robot1.torque", ElemType::Int);
  TagId count = signal(t, "cycle_count", ElemType::Udint);
  signal(t, "Cell.recipe", ElemType::String);
  auto change = [&](double s, TagId tag, uint64_t raw) {
    t.changes.push_back({static_cast<int64_t>(s * kS), tag, raw});
  };
  change(2, start, 1);
  change(2.5, start, 0);
  change(4, pos, realRaw(120.5));
  change(10, force, realRaw(1000.5));
  change(12, r1busy, 0);
  change(12, force, realRaw(3500.25));
  change(14, r1busy, 1);
  change(14, torque, static_cast<uint64_t>(int64_t{-5}));
  change(18, force, realRaw(0.0));
  change(35, r1busy, 0);
  change(35, torque, 0);
  change(38, err, 17);
  change(39, pos, realRaw(0.0));
  change(40, r1busy, 1);
  change(40, err, 0);
  change(52, r1busy, 0);
  change(55, force, realRaw(4000.0));
  change(66, force, realRaw(0.0));
  change(70, r1busy, 1);
  change(73, count, 1);

  t.endNs = 75 * kS;
  t.cycleStartNs = 2 * kS;
  t.cycleEndNs = 73 * kS;
  t.cyclesCompleted = 1;
  t.end = RunEnd::TimeLimit;
  t.endMessage = "time limit of 75 s reached";
  return t;
}

// The example trace as a run of three cycles, 0..30 s, 30..52 s and 52..73 s (30, 22 and 21 s):
// the measured cycle is the last one.
inline Trace threeCycleTrace() {
  Trace t = exampleCellTrace();
  t.cycles = {{0, 30 * kS}, {30 * kS, 52 * kS}, {52 * kS, 73 * kS}};
  t.cycleStartNs = 52 * kS;
  t.cycleEndNs = 73 * kS;
  t.cyclesCompleted = 3;
  return t;
}

}  // namespace virtcom::report::testing

namespace virtcom::report::testing {

// `cycles` copies of the example cycle back to back (75 s each): a long run for checking that
// the HTML stays small (sub-pixel bars merged, signal points capped); `window` bounds its
// activities as Trace::setWindow.
inline Trace longRunTrace(int cycles, size_t window = kDefaultTraceWindow) {
  Trace one = exampleCellTrace();
  Trace t;
  t.setWindow(window);
  t.devices = one.devices;
  t.labels = one.labels;
  t.signals = one.signals;
  t.totals = one.totals;
  for (int c = 0; c < cycles; ++c) {
    int64_t shift = c * one.endNs;
    for (ActivityRecord a : one.activities) {
      a.startNs += shift;
      if (a.endNs < 0) a.endNs = one.endNs;
      a.endNs += shift;
      t.activities.push_back(a);
    }
    for (SignalChange ch : one.changes) {
      ch.timeNs += shift;
      t.changes.push_back(ch);
    }
  }
  for (DeviceTotals& d : t.totals) d.energyJ *= cycles;
  t.endNs = cycles * one.endNs;
  t.cycleStartNs = one.cycleStartNs;
  t.cycleEndNs = one.cycleEndNs;
  t.cyclesCompleted = static_cast<uint32_t>(cycles);
  return t;
}

}  // namespace virtcom::report::testing
