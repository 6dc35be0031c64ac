#pragma once
// An industrial robot (the seed's ABB IRB 1600 / IRB 2600 running the RAPID main loop of
// Algorithm 3): numbered procedures made of steps (move, attach, detach, grip, release, screw,
// wait, require, set, clear), parsed and resolved to indices at load time.
//
// Motion: `move LOC` is a straight-line point-to-point move from wherever the robot is, with a
// trapezoidal (or, when short, triangular) speed profile from max_speed / acceleration, so its
// duration depends on where the robot comes from. actualX/Y/Z follow the profile.
// Zones: the robot occupies a location's zone from the start of the move into it until the end
// of the move out of it (World::enterZone/leaveZone with the procedure's label; a procedure
// started while standing in a zone relabels the occupation); it starts at `home`, occupying
// home's zone with the label "Idle".
// Energy: idle_power over the whole run; per move (1 + payload/payload_capacity) x
// (moving_power x distance/max_speed + accel_power x 2 x accelerationTime), payload = attached
// tool mass + held part mass. A procedure's activity carries the energy of its moves.
// Step effects on the world (facts, tool, held part) apply at the end of the step; checks
// (error 20/21/22/50) are made at its start.
#include <memory>
#include <string>
#include <vector>

#include "plant/motion_profile.hpp"
#include "plant/sequenced_device.hpp"

namespace virtcom::plant {

class Robot final : public SequencedDevice {
 public:
  enum class ToolKind : uint8_t { ParallelGripper, CentricGripper, Screwer, InsertHandler, Generic };
  enum class Op : uint8_t { Move, Attach, Detach, Grip, Release, Screw, Wait, Require, Set, Clear };

  struct Location {
    std::string name;
    double pos[3] = {0, 0, 0};  // m
    int32_t zone = -1;          // World zone id, -1 = none
  };
  struct Tool {
    std::string name;
    ToolKind kind = ToolKind::Generic;
    double massKg = 0;
    int64_t closeNs = 0, openNs = 0, rundownNs = 0;
    double finalTorqueNm = 0;
    int32_t magazine = -1;  // location index, -1 = anywhere
  };
  struct Part {
    uint32_t fact = 0;
    double massKg = 0.5;
    int32_t tool = -1;  // only this tool may grip it, -1 = any gripper
  };
  struct Step {
    Op op = Op::Wait;
    uint32_t arg = 0;    // location / tool / fact id / part index
    uint32_t arg2 = 0;   // second fact id (screw: the "<stud>Screwed" fact)
    int64_t ns = 0;      // wait duration
  };
  struct Procedure {
    int32_t number = 0;
    std::string name;
    uint32_t firstStep = 0, stepCount = 0;
    uint32_t label = 0;
  };
  struct Params {
    double maxSpeed = 0, accel = 0;           // m/s, m/s^2
    double payloadCapacityKg = 10;
    double idlePowerW = 0, movingPowerW = 0, accelPowerW = 0;
    int64_t toolChangeNs = 0;
    uint32_t home = 0;
    int32_t initialTool = -1;                 // index into tools attached at the start, -1 = none
    std::vector<Location> locations;
    std::vector<Tool> tools;
    std::vector<Part> parts;                   // fact -> mass/tool, for parts listed in `parts:`
    std::vector<Step> steps;                   // all procedures' steps, flat
    std::vector<Procedure> procedures;         // sorted by number
  };

  Robot(std::string name, Params params);

  static bool isGripper(ToolKind k) { return k != ToolKind::Screwer; }
  const Params& params() const { return p_; }
  bool changesParameter(std::string_view) const override { return true; }
  void swapParameters(Device& edited) override { swapKeepingLabels(p_, static_cast<Robot&>(edited).p_, &Params::procedures, proc_); }
  // Current state, for tests and reports.
  int32_t toolIndex() const { return tool_; }
  int32_t locationIndex() const { return location_; }
  double positionM(int axis) const { return pos_[axis]; }
  double payloadKg() const;

 protected:
  uint32_t commandLabel(double command) const override;
  int32_t beginCommand(double command, int64_t startNs, const StepContext& ctx) override;
  Progress advance(const StepContext& ctx, int64_t& atNs, int32_t& error) override;
  double commandEnergyJ() const override { return commandEnergyJ_; }
  // A move's position output changes every tick; other steps hold it until their end.
  int64_t modelNextEventNs() const override {
    return stepEndNs_ != INT64_MAX && p_.steps[stepIndex_].op == Op::Move ? 0 : stepEndNs_;
  }
  void writeOutputs(const StepContext& ctx) override;
  void prepareLabels(World& world, Trace& trace) override;

 private:
  const Procedure* findProcedure(double command) const;
  // Starts step `stepIndex_` at `t`: checks, duration, zone entry. 0 or an error code.
  int32_t beginStep(int64_t t, const StepContext& ctx);
  void completeStep(const StepContext& ctx);

  Params p_;
  size_t xPort_ = 0, yPort_ = 0, zPort_ = 0, toolPort_ = 0;
  uint32_t idleLabel_ = 0;
  // state
  double pos_[3] = {0, 0, 0};
  int32_t location_ = 0;
  int32_t tool_ = -1;
  int32_t heldPart_ = -1;   // fact id of the held part
  double heldMassKg_ = 0;
  // running procedure
  const Procedure* proc_ = nullptr;
  uint32_t stepIndex_ = 0;  // index into p_.steps
  int64_t stepStartNs_ = 0;
  int64_t stepEndNs_ = INT64_MAX;
  MotionProfile profile_;
  double from_[3] = {0, 0, 0};
  double dir_[3] = {0, 0, 0};
  double commandEnergyJ_ = 0;
};

std::unique_ptr<Device> makeRobot(const std::string& name, ConfigReader& cfg, World& world);

}  // namespace virtcom::plant
