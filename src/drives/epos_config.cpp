// The cell-file entry of an `s120_epos` positioning axis (docs/universal-axis.md lists every key).
#include <cmath>

#include "drives/drive_config.hpp"
#include "drives/epos_axis.hpp"
#include "plant/config_helpers.hpp"

namespace virtcom::drives {
namespace {

// Plain-number parameters (LU, 1000 LU/min, 1000 LU/s^2, rpm, %): key, member, must be > 0.
struct NumberKey {
  const char* key;
  double EposParams::*member;
  bool positive;
};
constexpr NumberKey kNumbers[] = {
    {"p2000", &EposParams::p2000, true},   {"p2506", &EposParams::p2506, true},   {"p2571", &EposParams::p2571, true},
    {"p2572", &EposParams::p2572, true},   {"p2573", &EposParams::p2573, true},   {"p2546", &EposParams::p2546, true},
    {"p2544", &EposParams::p2544, true},   {"p2542", &EposParams::p2542, true},   {"p2161", &EposParams::p2161, true},
    {"p2585", &EposParams::p2585, false},  {"p2586", &EposParams::p2586, false},  {"p2587", &EposParams::p2587, true},
    {"p2588", &EposParams::p2588, true},   {"p2599", &EposParams::p2599, false},  {"p2600", &EposParams::p2600, false},
    {"p2605", &EposParams::p2605, true},   {"p2606", &EposParams::p2606, false},  {"p2608", &EposParams::p2608, true},
    {"p2611", &EposParams::p2611, true},   {"ref_cam_pos", &EposParams::refCamPos, false},
    {"zero_mark_pos", &EposParams::zeroMarkPos, false}, {"zero_mark_pitch", &EposParams::zeroMarkPitch, true},
    {"p2580", &EposParams::p2580, false},  {"p2581", &EposParams::p2581, false},
    {"start_position", &EposParams::startPosition, false},
};
struct TimeKey {
  const char* key;
  double EposParams::*member;
};
constexpr TimeKey kTimes[] = {{"tau_x", &EposParams::tauXS}, {"p2545", &EposParams::p2545S}, {"p2543", &EposParams::p2543S}};

template <typename E>
struct Named {
  const char* name;
  E value;
};
using Task = TraversingBlock::Task;
using Advance = TraversingBlock::Advance;
constexpr Named<Task> kTasks[] = {{"positioning_abs", Task::PositionAbs}, {"positioning_rel", Task::PositionRel},
                                  {"endless_pos", Task::EndlessPos},      {"endless_neg", Task::EndlessNeg},
                                  {"wait", Task::Wait},                   {"goto", Task::Goto},
                                  {"set_o", Task::SetOutput},             {"reset_o", Task::ResetOutput}};
constexpr Named<Advance> kAdvances[] = {{"end", Advance::End},
                                        {"continue_with_stop", Advance::ContinueWithStop},
                                        {"continue_flying", Advance::ContinueFlying},
                                        {"continue_external", Advance::ContinueExternal}};

template <typename E, size_t N>
E named(ConfigReader& r, const char* key, const Named<E> (&table)[N], E fallback) {
  if (!r.has(key)) {
    r.child(key);
    return fallback;
  }
  const std::string text = r.requireString(key);
  std::string names;
  for (const auto& n : table) {
    if (text == n.name) return n.value;
    names += (names.empty() ? "" : ", ") + std::string(n.name);
  }
  r.error(r.node().find(key)->loc(), "'" + std::string(key) + "' must be one of: " + names + " (not '" + text + "')");
  return fallback;
}

void readBlocks(ConfigReader& cfg, EposParams& p) {
  const ConfigNode* list = cfg.child("blocks");
  if (!list) return;
  if (list->kind() != ConfigNode::Kind::List) {
    cfg.error(list->loc(), "'blocks' must be a list of traversing blocks such as [{number: 1, task: positioning_abs, position: 5000}]");
    return;
  }
  for (const ConfigNode& item : list->items()) {
    ConfigReader r(item, cfg.diags(), "traversing block");
    TraversingBlock b;
    const int64_t number = r.requireInt("number");
    if (number < 0 || number > 63) r.error(item.find("number") ? item.find("number")->loc() : item.loc(), "block 'number' must be 0..63");
    for (const auto& other : p.blocks)
      if (other.number == number) r.error(item.find("number")->loc(), "traversing block " + std::to_string(number) + " is defined twice");
    b.number = static_cast<uint8_t>(number);
    b.task = named(r, "task", kTasks, Task::PositionAbs);
    b.advance = named(r, "advance", kAdvances, Advance::End);
    b.position = static_cast<int32_t>(r.optInt("position", 0));
    b.velocity = static_cast<int32_t>(r.optInt("velocity", 100));
    b.accelPercent = r.optNumber("acceleration", 100);
    b.decelPercent = r.optNumber("deceleration", 100);
    b.parameter = static_cast<int32_t>(r.optInt("parameter", 0));
    if (!(b.accelPercent > 0 && b.accelPercent <= 100 && b.decelPercent > 0 && b.decelPercent <= 100))
      r.error(item.loc(), "block 'acceleration'/'deceleration' must be percentages in (0, 100]");
    r.rejectUnknownKeys();
    p.blocks.push_back(b);
  }
}

}  // namespace

std::unique_ptr<plant::Device> makeEposAxis(const std::string& name, ConfigReader& cfg, plant::World& world) {
  (void)world;
  if (cfg.optInt("telegram", 111) != 111) cfg.error(cfg.node().find("telegram")->loc(), "'telegram' of an s120_epos axis must be 111");
  DriveCommon common = readDriveCommon(cfg, TelegramId::Std111);
  EposParams p;
  for (const NumberKey& k : kNumbers)
    p.*k.member = k.positive ? positiveNumber(cfg, k.key, p.*k.member) : cfg.optNumber(k.key, p.*k.member);
  for (const TimeKey& k : kTimes) p.*k.member = positiveSeconds(cfg, k.key, p.*k.member);
  warnOnReferenceSpeed(cfg, common, p.p2000);
  p.hasRefCam = cfg.optBool("ref_cam", p.hasRefCam);
  p.probePos[0] = cfg.optNumber("probe1_pos", p.probePos[0]);
  p.probePos[1] = cfg.optNumber("probe2_pos", p.probePos[1]);
  p.monitoringNs = plant::optDurationNs(cfg, "monitoring_time", p.monitoringNs);
  p.solMonitor = cfg.optBool("sol_monitor", p.solMonitor);
  p.p0925 = static_cast<int>(cfg.optInt("p0925", p.p0925));
  const std::string commFault = cfg.optString("comm_fault", "F01910");
  if (commFault == "F08501") p.commFault = 8501;
  else if (commFault != "F01910")
    cfg.error(cfg.node().find("comm_fault")->loc(), "'comm_fault' must be F01910 (integrated fieldbus) or F08501 (PROFINET), not '" + commFault + "'");
  const std::string ack = cfg.optString("ack_mode", "toggle");
  p.ackMirror = ack == "mirror";
  if (ack != "toggle" && ack != "mirror") cfg.error(cfg.node().find("ack_mode")->loc(), "'ack_mode' must be toggle or mirror");
  if (p.p2580 > p.p2581) cfg.error(cfg.node().find("p2581") ? cfg.node().find("p2581")->loc() : cfg.node().loc(), "'p2581' (software limit plus) must not be below 'p2580'");
  readBlocks(cfg, p);
  return std::make_unique<EposAxis>(name, std::move(common), std::move(p));
}

}  // namespace virtcom::drives
