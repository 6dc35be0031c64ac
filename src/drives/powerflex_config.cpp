// Cell-file entries of the PowerFlex drives (types powerflex525, powerflex750), parameters by
// their PowerFlex numbers (P041 accel time 1, A431 jog frequency, C143 comm-loss action, ...).
#include "drives/drive_config.hpp"
#include "drives/powerflex.hpp"
#include "plant/config_helpers.hpp"

namespace virtcom::drives {
namespace {

// A 0/1 selection parameter; `expected` completes "'key' ..." in the error.
int64_t choice(ConfigReader& cfg, const std::string& key, int64_t fallback, const std::string& expected) {
  const int64_t v = cfg.optInt(key, fallback);
  if (v == 0 || v == 1) return v;
  cfg.error(cfg.node().find(key)->loc(), "'" + key + "' " + expected + ", not " + std::to_string(v));
  return fallback;
}

std::unique_ptr<plant::Device> makePowerFlex(const std::string& name, ConfigReader& cfg, TelegramId telegram,
                                             const char* type) {
  DriveCommon common = readDriveCommon(cfg, telegram);
  PowerFlexParams p;
  p.maxHz = positiveNumber(cfg, "p044", p.maxHz);
  p.minHz = cfg.optNumber("p043", p.minHz);
  p.accel1S = positiveSeconds(cfg, "p041", p.accel1S);
  p.decel1S = positiveSeconds(cfg, "p042", p.decel1S);
  p.accel2S = positiveSeconds(cfg, "a442", p.accel2S);
  p.decel2S = positiveSeconds(cfg, "a443", p.decel2S);
  p.jogHz = cfg.optNumber("a431", p.jogHz);
  p.jogRampS = positiveSeconds(cfg, "a432", p.jogRampS);
  const char* presetKeys[] = {"a410", "a411", "a412", "a413"};
  for (size_t i = 0; i < p.presetHz.size(); ++i) p.presetHz[i] = cfg.optNumber(presetKeys[i], p.presetHz[i]);
  p.polePairs = static_cast<int>(cfg.optInt("pole_pairs", 1));
  p.tauCoastS = positiveSeconds(cfg, "tau_coast", p.tauCoastS);
  p.commTimeoutNs = plant::optDurationNs(cfg, "comm_timeout", p.commTimeoutNs);
  const std::string action = cfg.optString("c143", "fault");
  if (action == "stop") p.commAction = CommLossAction::Stop;
  else if (action == "hold_last") p.commAction = CommLossAction::HoldLast;
  else if (action != "fault")
    cfg.error(cfg.node().find("c143")->loc(), "'c143' (comm loss action) must be fault, stop or hold_last, not '" + action + "'");
  const int64_t commFault = cfg.optInt("comm_fault", 83);
  if (commFault != 83 && commFault != 73)
    cfg.error(cfg.node().find("comm_fault")->loc(), "'comm_fault' must be 83 (EtherNet/IP comm loss) or 73 (net loss)");
  p.commFault = static_cast<uint16_t>(commFault);
  if (telegram == TelegramId::Pf525) {
    p.mop = cfg.optBool("mop", p.mop);
    p.mopTimeS = positiveSeconds(cfg, "a430", p.mopTimeS);
    p.mopSaveOnStop = choice(cfg, "a428", 1, "(MOP Reset Sel) must be 0 (Zero MOP Ref: a stop sets the MOP to 0) or 1 (Save MOP Ref)") == 1;
    p.mopPreload = choice(cfg, "a429", 0, "(MOP Preload) must be 0 (no preload) or 1 (selecting the MOP loads the output frequency)") == 1;
  }
  if (telegram == TelegramId::Pf750) {
    const std::string unit = cfg.optString("speed_units", "hz");
    if (unit != "hz" && unit != "rpm") cfg.error(cfg.node().find("speed_units")->loc(), "'speed_units' must be hz or rpm");
    p.referenceInRpm = unit == "rpm";
    const std::string mode = cfg.optString("control_mode", "speed");
    if (mode != "speed" && mode != "position")
      cfg.error(cfg.node().find("control_mode")->loc(), "'control_mode' must be speed or position, not '" + mode + "'");
    p.positionMode = mode == "position";
    if (p.positionMode && p.referenceInRpm)
      cfg.error(cfg.node().find("speed_units")->loc(), "'speed_units' does not apply with 'control_mode: position' (the reference is in degrees)");
  }
  if (p.polePairs < 1) cfg.error(cfg.node().find("pole_pairs")->loc(), "'pole_pairs' must be at least 1");
  if (p.minHz < 0 || p.minHz > p.maxHz) cfg.error(cfg.node().loc(), "'p043' must be between 0 and 'p044'");
  return std::make_unique<PowerFlex>(name, type, std::move(common), p);
}

}  // namespace

std::unique_ptr<plant::Device> makePowerFlex525(const std::string& name, ConfigReader& cfg, plant::World& world) {
  (void)world;
  return makePowerFlex(name, cfg, TelegramId::Pf525, "powerflex525");
}

std::unique_ptr<plant::Device> makePowerFlex750(const std::string& name, ConfigReader& cfg, plant::World& world) {
  (void)world;
  return makePowerFlex(name, cfg, TelegramId::Pf750, "powerflex750");
}

}  // namespace virtcom::drives
