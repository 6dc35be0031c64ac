#pragma once
// Test-only fixture: devices loaded from MiniYaml snippets, ports bound to a TagBus as
// "<device>.<port>", stepped in virtual time (1 ms ticks unless told otherwise).
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/config_node.hpp"
#include "core/diagnostics.hpp"
#include "core/source.hpp"
#include "core/tag_bus.hpp"
#include "core/trace.hpp"
#include "mini_yaml.hpp"
#include "plant/device.hpp"
#include "plant/world.hpp"

namespace virtcom::plant::test {

inline constexpr int64_t kMs = 1'000'000;
inline constexpr int64_t kS = 1'000'000'000;

class PlantRig {
 public:
  // Loads `yaml` (a device entry without `type`) as device `name` of `type`; null on errors
  // (see diags). The device is kept and stepped by tick().
  Device* add(const std::string& type, const std::string& name, const std::string& yaml) {
    uint32_t file = sources.addFile(name + ".yaml", yaml);
    nodes_.push_back(std::make_unique<ConfigNode>(MiniYaml::parse(yaml, file)));
    ConfigReader reader(*nodes_.back(), diags, "device '" + name + "'");
    const size_t errorsBefore = diags.errorCount();
    std::unique_ptr<Device> d = createDevice(type, name, reader, world);
    if (!d || diags.errorCount() > errorsBefore) return nullptr;  // a device with mistakes must not run
    for (size_t i = 0; i < d->ports().size(); ++i) d->bindPort(i, bus.add(name + "." + d->ports()[i].name, d->ports()[i].type));
    devices_.push_back(std::move(d));
    return devices_.back().get();
  }
  // Prepares every device (once, before the first tick).
  void prepare() {
    for (auto& d : devices_) d->prepare(world, trace);
    prepared_ = true;
  }
  // Advances virtual time by dtNs and steps every device in load order.
  void tick(int64_t dtNs = kMs) {
    if (!prepared_) prepare();
    now += dtNs;
    StepContext ctx{now, dtNs, bus, world, trace};
    for (auto& d : devices_) d->step(ctx);
  }
  // Ticks until pred() holds (true) or limitNs of virtual time passed (false).
  bool tickUntil(const std::function<bool()>& pred, int64_t limitNs = 60 * kS, int64_t dtNs = kMs) {
    const int64_t end = now + limitNs;
    while (now < end) {
      tick(dtNs);
      if (pred()) return true;
    }
    return false;
  }
  void finish() {
    for (auto& d : devices_) d->finish(now, trace);
  }

  TagId tagOf(const std::string& signal) const {
    TagId t = bus.find(signal);
    EXPECT_NE(t, kNoTag) << signal;
    return t;
  }
  void setBool(const std::string& s, bool v) { bus.setBool(tagOf(s), v); }
  void setNumber(const std::string& s, double v) { bus.setNumber(tagOf(s), v); }
  bool getBool(const std::string& s) const { return bus.getBool(tagOf(s)); }
  double getNumber(const std::string& s) const { return bus.getNumber(tagOf(s)); }
  bool fact(const std::string& name) { return world.hasFact(world.fact(name)); }
  void setFact(const std::string& name, bool v) { world.setFact(world.fact(name), v); }
  const std::string& label(const ActivityRecord& a) const { return trace.labels[a.label]; }
  std::string renderedDiags() const { return diags.render(sources); }

  SourceManager sources;
  Diagnostics diags;
  Trace trace;
  World world{trace};
  TagBus bus;
  int64_t now = 0;

 private:
  std::vector<std::unique_ptr<ConfigNode>> nodes_;
  std::vector<std::unique_ptr<Device>> devices_;
  bool prepared_ = false;
};

}  // namespace virtcom::plant::test
