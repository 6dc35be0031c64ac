#include "drives/drive_config.hpp"

#include <cmath>
#include <cstdio>

#include "core/cell_diagnostic_codes.hpp"
#include "plant/config_helpers.hpp"

namespace virtcom::drives {

double positiveSeconds(ConfigReader& cfg, const std::string& key, double fallbackS) {
  const double v = cfg.optQuantity(key, Dimension::Time, fallbackS);
  if (!(v > 0)) cfg.error(cfg.node().find(key)->loc(), "'" + key + "' must be a time greater than 0");
  return v > 0 ? v : fallbackS;
}

double nonNegativeSeconds(ConfigReader& cfg, const std::string& key, double fallbackS) {
  const double v = cfg.optQuantity(key, Dimension::Time, fallbackS);
  if (!(v >= 0)) cfg.error(cfg.node().find(key)->loc(), "'" + key + "' must be a time of 0 or more");
  return v >= 0 ? v : fallbackS;
}

double positiveNumber(ConfigReader& cfg, const std::string& key, double fallback) {
  const double v = cfg.optNumber(key, fallback);
  if (!(v > 0)) cfg.error(cfg.node().find(key)->loc(), "'" + key + "' must be a number greater than 0");
  return v > 0 ? v : fallback;
}

double nonNegativeNumber(ConfigReader& cfg, const std::string& key, double fallback) {
  const double v = cfg.optNumber(key, fallback);
  if (!(v >= 0)) cfg.error(cfg.node().find(key)->loc(), "'" + key + "' must be a number of 0 or more");
  return v >= 0 ? v : fallback;
}

namespace {

// `mapping:` is a map here: the cell loader replaces a file name by the file's tree.
void readMapping(ConfigReader& cfg, DriveCommon& c) {
  const ConfigNode* node = cfg.child("mapping");
  if (!node) return;
  if (node->kind() != ConfigNode::Kind::Map) {
    cfg.error(node->loc(), "'mapping' must name a mapping file such as lib/mappings/telegram1.yaml or be an inline map");
    return;
  }
  auto spec = parseMapping(*node, cfg.diags());
  if (!spec) return;
  if (spec->telegram != c.telegram) {
    cfg.error(cfg.node().keyLoc("mapping"), "the mapping is for telegram " + std::string(telegram(spec->telegram).key) + " but this drive speaks " +
                               std::string(telegram(c.telegram).key));
    return;
  }
  c.mapping = std::make_shared<const MappingSpec>(std::move(*spec));
}

}  // namespace

namespace {
std::string rpmText(double rpm) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", rpm);
  return text;
}
}  // namespace

void warnOnReferenceSpeed(ConfigReader& cfg, const DriveCommon& common, double p2000) {
  if (!common.mapping) return;
  for (const auto& ref : common.mapping->referenceSpeeds) {
    if (std::abs(ref.rpm - p2000) <= 1e-9 * p2000) continue;
    cfg.diags().warning(celldiag::C012, ref.loc,
                        "the mapping's " + std::string(ref.key) + " is " + rpmText(ref.rpm) + " rpm but the drive's p2000 is " +
                            rpmText(p2000) + " rpm: the PLC reads every speed scaled by " + rpmText(p2000) + "/" +
                            rpmText(ref.rpm) + " (set both to the drive's reference speed)");
  }
}

DriveCommon readDriveCommon(ConfigReader& cfg, TelegramId telegram) {
  DriveCommon c;
  c.telegram = telegram;
  c.stepNs = plant::optDurationNs(cfg, "step", 1'000'000);
  if (c.stepNs < 1000) {
    cfg.error(cfg.node().find("step")->loc(), "'step' must be at least 1 us");
    c.stepNs = 1'000'000;
  }
  readMapping(cfg, c);
  if (const ConfigNode* load = cfg.child("load")) {
    if (load->kind() != ConfigNode::Kind::Map) {
      cfg.error(load->loc(), "'load' must be a map such as {gear_ratio: 5, lead: 10 mm, inertia_kgm2: 0.01, torque: 2 Nm}");
      return c;
    }
    ConfigReader l(*load, cfg.diags(), "'load'");
    c.load.gearRatio = positiveNumber(l, "gear_ratio", 1.0);
    c.load.mmPerRev = l.optQuantity("lead", Dimension::Length, 0.0) * 1e3;
    c.load.inertiaKgm2 = l.optNumber("inertia_kgm2", c.load.inertiaKgm2);
    c.load.loadTorqueNm = l.optQuantity("torque", Dimension::Torque, 0.0);
    if (c.load.mmPerRev < 0 || c.load.inertiaKgm2 < 0 || c.load.loadTorqueNm < 0)
      l.error(load->loc(), "'load': lead, inertia_kgm2 and torque must not be negative");
    l.rejectUnknownKeys();
  }
  return c;
}

}  // namespace virtcom::drives
