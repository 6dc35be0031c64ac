#pragma once
// Steering a running simulation from outside it (the live HMI: pause, single step, speed,
// writes into the PLC): one call on the simulation's own thread before every base tick, where
// the simulation is between ticks and may be changed safely.
namespace virtcom::sim {

class Simulation;

class RunControl {
 public:
  virtual ~RunControl() = default;
  // Before every base tick, on the simulation's thread. May block (while paused; it must then
  // return within about 100 ms of an interrupt) and act on `sim` (setSpeed, resumePacing, the
  // PLC's memory). False ends the run now, as interrupted. Must not allocate while nothing is
  // asked of it.
  virtual bool beforeTick(Simulation& sim) = 0;
  // Read when beforeTick() returned false: true if the run ends to be started again from its
  // initial state (the HMI's reset), which the trace's end message then says ("reset").
  virtual bool resetting() const { return false; }
};

}  // namespace virtcom::sim
