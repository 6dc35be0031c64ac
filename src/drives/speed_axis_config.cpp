// Cell-file entry of a Siemens speed axis (type g120): telegram 1 or 352, SINAMICS parameters.
#include "drives/drive_config.hpp"
#include "drives/speed_axis.hpp"
#include "plant/config_helpers.hpp"

namespace virtcom::drives {

std::unique_ptr<plant::Device> makeSpeedAxis(const std::string& name, ConfigReader& cfg, plant::World& world) {
  (void)world;
  const int64_t telegramNumber = cfg.optInt("telegram", 1);
  TelegramId telegram = TelegramId::Std1;
  if (telegramNumber == 352) telegram = TelegramId::Siemens352;
  else if (telegramNumber != 1)
    cfg.error(cfg.node().find("telegram")->loc(), "'telegram' of a g120 speed axis must be 1 or 352, not " +
                                                      std::to_string(telegramNumber));
  DriveCommon common = readDriveCommon(cfg, telegram);
  SpeedAxisParams p;
  p.p2000 = positiveNumber(cfg, "p2000", p.p2000);
  warnOnReferenceSpeed(cfg, common, p.p2000);
  p.p1082 = positiveNumber(cfg, "p1082", p.p2000);
  p.p1120S = positiveSeconds(cfg, "p1120", p.p1120S);
  p.p1121S = positiveSeconds(cfg, "p1121", p.p1121S);
  p.p1135S = positiveSeconds(cfg, "p1135", p.p1135S);
  p.tauSpeedS = positiveSeconds(cfg, "tau_speed", p.tauSpeedS);
  p.tauCoastS = positiveSeconds(cfg, "tau_coast", p.tauCoastS);
  p.p0045S = positiveSeconds(cfg, "p0045", p.p0045S);
  p.p1226 = positiveNumber(cfg, "p1226", p.p1226);
  p.p1228S = positiveSeconds(cfg, "p1228", p.p1228S);
  p.p1227S = positiveSeconds(cfg, "p1227", p.p1227S);
  p.p2163 = positiveNumber(cfg, "p2163", p.p2163);
  p.p2164 = nonNegativeNumber(cfg, "p2164", p.p2164);
  p.p2166S = nonNegativeSeconds(cfg, "p2166", p.p2166S);
  p.mop = cfg.optBool("mop", p.mop);
  p.p1047S = positiveSeconds(cfg, "p1047", p.p1047S);
  p.p1040 = nonNegativeNumber(cfg, "p1040", p.p1040);
  if (p.p1040 > p.p1082) cfg.error(cfg.node().find("p1040")->loc(), "'p1040' (MOP start value) must not exceed p1082 (the maximum speed)");
  const int64_t p1030 = cfg.optInt("p1030", 0);
  if (p1030 != 0 && p1030 != 1)
    cfg.error(cfg.node().find("p1030")->loc(), "'p1030' (MOP configuration) must be 0 (the MOP starts from p1040 at every ON) or 1 "
                                               "(bit 0, data save: it keeps its setpoint); its other bits are not simulated");
  p.p1030Store = p1030 == 1;
  p.p2141 = positiveNumber(cfg, "p2141", 0.01 * p.p2000);
  p.p2002 = positiveNumber(cfg, "p2002", p.p2002);
  p.p2003 = cfg.optQuantity("p2003", Dimension::Torque, p.p2003);
  p.torqueLimitNm = cfg.optQuantity("torque_limit", Dimension::Torque, 2 * p.p2003);
  p.noLoadCurrent = cfg.optNumber("no_load_current", p.noLoadCurrent);
  p.monitoringNs = plant::optDurationNs(cfg, "monitoring_time", p.monitoringNs);
  p.brake = cfg.optBool("brake", false);
  const std::string commFault = cfg.optString("comm_fault", "F01910");
  if (commFault == "F08501") p.commFault = 8501;
  else if (commFault != "F01910")
    cfg.error(cfg.node().find("comm_fault")->loc(), "'comm_fault' must be F01910 (integrated fieldbus) or F08501 (PROFINET), not '" + commFault + "'");
  if (p.p2003 <= 0 || p.torqueLimitNm <= 0) cfg.error(cfg.node().loc(), "'p2003' and 'torque_limit' must be greater than 0 Nm");
  return std::make_unique<SpeedAxis>(name, std::move(common), p);
}

}  // namespace virtcom::drives
