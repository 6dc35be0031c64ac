#pragma once
// The real PLC's SFC position while `virtcom monitor` watches it over ADS: every step of the
// cell's own program (its X flag and T time, by the names the program gives them:
// "MAIN.Step2.X") read from the PLC with the cell's wiring, and copied after each poll into an
// image laid out as that program's memory, so the HMI's SFC panel reads the real PLC's steps
// as it reads a soft PLC's. The flags are signals of the watched run, so the historian records
// them too.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bytecode/module.hpp"
#include "cell/cell.hpp"
#include "core/trace.hpp"
#include "lang/sfc/step_monitor.hpp"

namespace virtcom::cli {

class SfcMirror final : public TraceSink {
 public:
  // `program`: the cell's compiled program, whose charts the plant's PLC is expected to run.
  explicit SfcMirror(std::unique_ptr<bc::Module> program);

  bool empty() const { return steps_.empty(); }
  // Every step's X and T as observed-only wires (skipped if the PLC lacks them).
  void addWires(std::vector<cell::ExternalWire>& wires) const;
  // Once the bridge has connected: the bus tags it gave the flags it found. Returns how many
  // steps the PLC has (the others stay inactive in the image).
  size_t bind(const TagBus& bus);

  void begin(const Trace&) override {}
  void change(const SignalChange&) override {}
  void tick(const Trace&, int64_t) override;  // the last poll's flags into the image
  void end(const Trace&) override {}

  const std::vector<sfc::StepVariable>& steps() const { return steps_; }
  const uint8_t* image() const { return image_.data(); }
  size_t imageSize() const { return image_.size(); }
  // The active steps' paths, separated by spaces ("" if none).
  std::string activeSteps() const;

 private:
  struct Bound {
    uint32_t step;  // index into steps_
    TagId x, t;
  };
  std::unique_ptr<bc::Module> program_;
  std::vector<sfc::StepVariable> steps_;
  std::vector<uint8_t> image_;
  std::vector<Bound> bound_;
  const TagBus* bus_ = nullptr;
};

}  // namespace virtcom::cli
