#include "cli/sfc_mirror.hpp"

#include "core/value_codec.hpp"

namespace virtcom::cli {

SfcMirror::SfcMirror(std::unique_ptr<bc::Module> program) : program_(std::move(program)) {
  if (!program_) return;
  steps_ = sfc::findSteps(*program_);
  image_.assign(program_->staticSize, 0);
}

void SfcMirror::addWires(std::vector<cell::ExternalWire>& wires) const {
  for (const sfc::StepVariable& s : steps_)
    for (const char* flag : {".X", ".T"}) wires.push_back({kNoTag, plant::PortDir::In, s.path + flag, {}, {}, true, -1});
}

size_t SfcMirror::bind(const TagBus& bus) {
  bus_ = &bus;
  bound_.clear();
  for (uint32_t i = 0; i < steps_.size(); ++i) {
    const TagId x = bus.find(steps_[i].path + ".X"), t = bus.find(steps_[i].path + ".T");
    if (x != kNoTag && t != kNoTag) bound_.push_back({i, x, t});
  }
  return bound_.size();
}

void SfcMirror::tick(const Trace&, int64_t) {
  for (const Bound& b : bound_) {
    const sfc::StepVariable& s = steps_[b.step];
    storeVariable(image_.data() + s.activeAddress, -1, ElemType::Bool, *bus_, b.x);
    storeVariable(image_.data() + s.timeAddress, -1, ElemType::Time, *bus_, b.t);
  }
}

std::string SfcMirror::activeSteps() const {
  std::string out;
  sfc::formatActiveSteps(steps_, image_.data(), out);
  return out;
}

}  // namespace virtcom::cli
