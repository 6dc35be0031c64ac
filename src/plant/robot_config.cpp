// Loading a robot from its cell-file entry: locations, tools, parts and procedures, with every
// name resolved to an index here so the per-tick path never sees a string.
#include <algorithm>
#include <cctype>

#include "plant/config_helpers.hpp"
#include "plant/robot.hpp"

namespace virtcom::plant {
namespace {

struct ToolKindName {
  const char* name;
  Robot::ToolKind kind;
};
constexpr ToolKindName kToolKinds[] = {
    {"parallel_gripper", Robot::ToolKind::ParallelGripper}, {"centric_gripper", Robot::ToolKind::CentricGripper},
    {"screwer", Robot::ToolKind::Screwer},                  {"insert_handler", Robot::ToolKind::InsertHandler},
    {"generic", Robot::ToolKind::Generic},
};

struct OpName {
  const char* name;
  Robot::Op op;
  const char* argument;  // what follows the keyword, for messages; null = nothing
};
constexpr OpName kOps[] = {
    {"move", Robot::Op::Move, "a location"},   {"attach", Robot::Op::Attach, "a tool"},
    {"detach", Robot::Op::Detach, nullptr},    {"grip", Robot::Op::Grip, "a part (fact)"},
    {"release", Robot::Op::Release, "a part (fact)"}, {"screw", Robot::Op::Screw, "a stud (fact)"},
    {"wait", Robot::Op::Wait, "a duration"},   {"require", Robot::Op::Require, "a fact"},
    {"set", Robot::Op::Set, "a fact"},         {"clear", Robot::Op::Clear, "a fact"},
};

std::string trim(const std::string& s) {
  size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

template <typename T>
int32_t indexByName(const std::vector<T>& items, const std::string& name) {
  for (size_t i = 0; i < items.size(); ++i)
    if (items[i].name == name) return static_cast<int32_t>(i);
  return -1;
}

template <typename T>
std::string namesOf(const std::vector<T>& items) {
  std::vector<std::string> names;
  for (const auto& i : items) names.push_back(i.name);
  return names.empty() ? "none defined" : joinNames(names);
}

class RobotLoader {
 public:
  RobotLoader(const std::string& name, ConfigReader& cfg, World& world) : name_(name), cfg_(cfg), world_(world) {}

  void load(Robot::Params& p) {
    p.maxSpeed = cfg_.requireQuantity("max_speed", Dimension::Speed);
    p.accel = cfg_.requireQuantity("acceleration", Dimension::Acceleration);
    positive(p.maxSpeed, "max_speed");
    positive(p.accel, "acceleration");
    p.payloadCapacityKg = cfg_.optQuantity("payload_capacity", Dimension::Mass, 10.0);
    positive(p.payloadCapacityKg, "payload_capacity");
    p.idlePowerW = cfg_.optQuantity("idle_power", Dimension::Power, 0);
    p.movingPowerW = cfg_.optQuantity("moving_power", Dimension::Power, 0);
    p.accelPowerW = cfg_.optQuantity("accel_power", Dimension::Power, 0);
    loadLocations(p);
    p.toolChangeNs = optDurationNs(cfg_, "tool_change_time", 0);
    loadTools(p);
    if (!p.tools.empty() && !cfg_.has("tool_change_time"))
      cfg_.error(cfg_.node().keyLoc("tools"), "robot '" + name_ + "' has tools but no 'tool_change_time'");
    // A cell often starts with the tool already on the flange; without this the first procedure
    // would have to fetch it.
    const std::string initialTool = cfg_.optString("initial_tool", "");
    if (!initialTool.empty()) {
      p.initialTool = indexByName(p.tools, initialTool);
      if (p.initialTool < 0)
        error(cfg_.node().find("initial_tool")->loc(),
              "unknown tool '" + initialTool + "' (expected one of: " + namesOf(p.tools) + ")");
    }
    loadParts(p);
    const std::string home = cfg_.optString("home", p.locations.empty() ? "" : p.locations.front().name);
    if (!p.locations.empty()) {
      int32_t h = indexByName(p.locations, home);
      if (h < 0)
        cfg_.error(cfg_.node().find("home")->loc(),
                   "unknown home location '" + home + "' (expected one of: " + namesOf(p.locations) + ")");
      p.home = static_cast<uint32_t>(std::max(h, 0));
    }
    loadProcedures(p);
  }

 private:
  void error(SourceLocation loc, std::string msg) { cfg_.error(loc, std::move(msg)); }
  void positive(double v, const char* key) {
    if (cfg_.has(key) && !(v > 0)) error(cfg_.node().find(key)->loc(), std::string("'") + key + "' must be greater than 0");
  }

  void loadLocations(Robot::Params& p) {
    const ConfigNode* locs = mapChild(cfg_, "locations", true);
    if (!locs) return;
    ConfigReader r(*locs, cfg_.diags(), "locations of robot '" + name_ + "'");
    for (const auto& [locName, node] : locs->entries()) {
      Robot::Location loc;
      loc.name = locName;
      if (node.kind() == ConfigNode::Kind::Map) {
        ConfigReader lr(node, cfg_.diags(), "location '" + locName + "'");
        auto v = lr.requireVector("at", Dimension::Length, 3);
        std::copy_n(v.begin(), 3, loc.pos);
        std::string zone = lr.optString("zone", "");
        if (!zone.empty()) loc.zone = static_cast<int32_t>(world_.zone(zone));
        lr.rejectUnknownKeys();
      } else {
        auto v = r.requireVector(locName, Dimension::Length, 3);
        std::copy_n(v.begin(), 3, loc.pos);
      }
      p.locations.push_back(std::move(loc));
    }
    if (p.locations.empty()) error(locs->loc(), "robot '" + name_ + "' needs at least one location");
  }

  void loadTools(Robot::Params& p) {
    const ConfigNode* tools = mapChild(cfg_, "tools", false);
    if (!tools) return;
    for (const auto& [toolName, node] : tools->entries()) {
      Robot::Tool tool;
      tool.name = toolName;
      ConfigReader tr(node, cfg_.diags(), "tool '" + toolName + "'");
      if (node.kind() == ConfigNode::Kind::Map) {
        const std::string kind = tr.requireString("kind");
        bool found = false;
        std::vector<std::string> kinds;
        for (const auto& k : kToolKinds) {
          kinds.push_back(k.name);
          if (kind == k.name) {
            tool.kind = k.kind;
            found = true;
          }
        }
        if (!found && tr.has("kind"))
          error(node.find("kind")->loc(), "unknown tool kind '" + kind + "' (expected one of: " + joinNames(kinds) + ")");
        tool.massKg = tr.optQuantity("mass", Dimension::Mass, 0);
        const bool screwer = tool.kind == Robot::ToolKind::Screwer;
        tool.closeNs = optDurationNs(tr, "close_time", screwer ? 0 : 500'000'000);
        tool.openNs = optDurationNs(tr, "open_time", screwer ? 0 : 500'000'000);
        tool.rundownNs = screwer ? requireDurationNs(tr, "rundown_time") : optDurationNs(tr, "rundown_time", 0);
        tool.finalTorqueNm = tr.optQuantity("final_torque", Dimension::Torque, 0);
        const std::string magazine = tr.optString("magazine", "");
        if (!magazine.empty()) {
          tool.magazine = indexByName(p.locations, magazine);
          if (tool.magazine < 0)
            error(node.find("magazine")->loc(),
                  "unknown magazine location '" + magazine + "' (expected one of: " + namesOf(p.locations) + ")");
        }
        tr.rejectUnknownKeys();
      }
      p.tools.push_back(std::move(tool));
    }
  }

  void loadParts(Robot::Params& p) {
    const ConfigNode* parts = mapChild(cfg_, "parts", false);
    if (!parts) return;
    ConfigReader r(*parts, cfg_.diags(), "parts of robot '" + name_ + "'");
    for (const auto& [partName, node] : parts->entries()) {
      Robot::Part part;
      part.fact = world_.fact(partName);
      if (node.kind() == ConfigNode::Kind::Map) {
        ConfigReader pr(node, cfg_.diags(), "part '" + partName + "'");
        part.massKg = pr.optQuantity("mass", Dimension::Mass, 0.5);
        const std::string tool = pr.optString("tool", "");
        if (!tool.empty()) {
          part.tool = indexByName(p.tools, tool);
          if (part.tool < 0)
            error(node.find("tool")->loc(), "unknown tool '" + tool + "' (expected one of: " + namesOf(p.tools) + ")");
        }
        pr.rejectUnknownKeys();
      } else {
        part.massKg = r.requireQuantity(partName, Dimension::Mass);
      }
      p.parts.push_back(part);
    }
  }

  uint32_t partIndex(Robot::Params& p, const std::string& fact) {
    const uint32_t id = world_.fact(fact);
    for (size_t i = 0; i < p.parts.size(); ++i)
      if (p.parts[i].fact == id) return static_cast<uint32_t>(i);
    p.parts.push_back({id, 0.5, -1});
    return static_cast<uint32_t>(p.parts.size() - 1);
  }

  void loadProcedures(Robot::Params& p) {
    const ConfigNode* procs = mapChild(cfg_, "procedures", true);
    if (!procs) return;
    for (const auto& [key, node] : procs->entries()) {
      Robot::Procedure proc;
      parseCommandNumber(cfg_, key, procs->keyLoc(key), proc.number);
      for (const auto& other : p.procedures)
        if (other.number == proc.number && proc.number != 0) error(node.loc(), "procedure number " + key + " is defined twice");
      ConfigReader pr(node, cfg_.diags(), "procedure " + key + " of robot '" + name_ + "'");
      proc.name = pr.requireString("name");
      proc.firstStep = static_cast<uint32_t>(p.steps.size());
      const ConfigNode* steps = pr.child("steps");
      if (!steps) {
        pr.error(node.loc(), "procedure " + key + " needs 'steps' (a list such as [move Home, attach Gripper1])");
      } else if (steps->kind() != ConfigNode::Kind::List) {
        pr.error(steps->loc(), "'steps' must be a list such as [move Home, attach Gripper1]");
      } else {
        for (const auto& item : steps->items()) loadStep(p, item);
      }
      proc.stepCount = static_cast<uint32_t>(p.steps.size()) - proc.firstStep;
      pr.rejectUnknownKeys();
      p.procedures.push_back(std::move(proc));
    }
    std::stable_sort(p.procedures.begin(), p.procedures.end(),
                     [](const Robot::Procedure& a, const Robot::Procedure& b) { return a.number < b.number; });
  }

  void loadStep(Robot::Params& p, const ConfigNode& item) {
    if (item.kind() != ConfigNode::Kind::Scalar) {
      error(item.loc(), "a step must be a single line such as 'move Home' or 'wait 0.5 s'");
      return;
    }
    const std::string text = trim(item.scalar());
    const size_t space = text.find_first_of(" \t");
    const std::string keyword = text.substr(0, space);
    const std::string arg = space == std::string::npos ? "" : trim(text.substr(space));
    const OpName* op = nullptr;
    std::vector<std::string> keywords;
    for (const auto& o : kOps) {
      keywords.push_back(o.name);
      if (keyword == o.name) op = &o;
    }
    if (!op) {
      error(item.loc(), "unknown step '" + keyword + "' (expected one of: " + joinNames(keywords) + ")");
      return;
    }
    if (op->argument && arg.empty()) return error(item.loc(), "'" + keyword + "' needs " + op->argument);
    if (!op->argument && !arg.empty()) return error(item.loc(), "'" + keyword + "' takes no argument, found '" + arg + "'");
    Robot::Step s;
    s.op = op->op;
    switch (op->op) {
      case Robot::Op::Move: {
        int32_t i = indexByName(p.locations, arg);
        if (i < 0) return error(item.loc(), "unknown location '" + arg + "' (expected one of: " + namesOf(p.locations) + ")");
        s.arg = static_cast<uint32_t>(i);
        break;
      }
      case Robot::Op::Attach: {
        int32_t i = indexByName(p.tools, arg);
        if (i < 0) return error(item.loc(), "unknown tool '" + arg + "' (expected one of: " + namesOf(p.tools) + ")");
        s.arg = static_cast<uint32_t>(i);
        break;
      }
      case Robot::Op::Grip:
      case Robot::Op::Release: s.arg = partIndex(p, arg); break;
      case Robot::Op::Screw:
        s.arg = world_.fact(arg);
        s.arg2 = world_.fact(arg + "Screwed");
        break;
      case Robot::Op::Wait: {
        double seconds = 0;
        std::string problem = parseQuantity(arg, Dimension::Time, seconds);
        if (!problem.empty()) return error(item.loc(), "'wait': " + problem);
        if (seconds < 0) return error(item.loc(), "'wait' needs a duration >= 0");
        s.ns = secondsToNs(seconds);
        break;
      }
      case Robot::Op::Require:
      case Robot::Op::Set:
      case Robot::Op::Clear: s.arg = world_.fact(arg); break;
      case Robot::Op::Detach: break;
    }
    p.steps.push_back(s);
  }

  const std::string& name_;
  ConfigReader& cfg_;
  World& world_;
};

}  // namespace

std::unique_ptr<Device> makeRobot(const std::string& name, ConfigReader& cfg, World& world) {
  Robot::Params p;
  RobotLoader(name, cfg, world).load(p);
  return std::make_unique<Robot>(name, std::move(p));
}

}  // namespace virtcom::plant
