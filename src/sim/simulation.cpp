#include "sim/simulation.hpp"

#include <algorithm>

#include "core/value_codec.hpp"

namespace virtcom::sim {

namespace {

Simulation::WireSlot slotOf(const cell::Wire& w) { return {w.address, w.tag, w.bit, w.varType}; }

bool isInputArea(const cell::Wire& w, const bc::ProcessArea& in) {
  return w.address >= in.address && w.address < in.address + in.size;
}

}  // namespace

Simulation::Simulation(cell::Cell& cell, SimOptions options) : cell_(cell), options_(options) {
  if (options_.speed > 0 || options_.control) {
    auto paced = std::make_unique<PacedClock>(options_.speed > 0 ? options_.speed : 1.0);
    paced_ = paced.get();
    clock_ = std::move(paced);
  } else {
    clock_ = std::make_unique<VirtualClock>();
  }
  if (cell_.module) {
    plc::RuntimeOptions ropts;
    ropts.skipRepeatedScans = options_.skipRepeatedScans;
    runtime_ = std::make_unique<plc::Runtime>(*cell_.module, *clock_, ropts);
    runtime_->machine().useCompiled(options_.compiled);
    runtime_->switchToCompiledWhenReady(options_.tierUp);
  }
  timeLimitNs_ = options_.timeLimitNs >= 0 ? options_.timeLimitNs : cell_.run.timeLimitNs;
  jumps_ = options_.eventTime && !paced_ && options_.bridges.empty() && !options_.control && !options_.watch.enabled &&
           !options_.beforeScan && (!options_.afterScan || options_.afterScanSeesJumps);
  Trace& trace = cell_.trace;
  trace.time = {jumps_, 0, 0, 0};
  for (auto& d : cell_.devices) d->prepare(cell_.world, trace);
  if (options_.watch.enabled)
    recogniser_ = std::make_unique<OperationRecogniser>(cell_.devices, trace, options_.watch.model, options_.watch.threshold);
  for (const cell::Wire& w : cell_.wires) {
    if (w.dir == plant::PortDir::In) fromPlc_.push_back(slotOf(w));
    else if (!runtime_ || !isInputArea(w, cell_.module->inputs)) toPlc_.push_back(slotOf(w));
    else toInputImage_.push_back({w.address - cell_.module->inputs.address, w.tag, w.bit, w.varType});
  }
  // Extra PLC variables to record get their own tags.
  for (const auto& name : cell_.run.recordVars) {
    auto ref = bc::resolveVariable(*cell_.module, name);
    const bc::TypeDesc& t = cell_.module->types[ref->type];
    fromPlc_.push_back(slotOf(cell::makeWire(cell_.bus.add(name, t.elem), plant::PortDir::In, *ref, t.elem, name)));
  }
  if (!cell_.run.cycleDoneVar.empty()) {
    auto ref = bc::resolveVariable(*cell_.module, cell_.run.cycleDoneVar);
    cycleWire_.address = ref->address;
    cycleWire_.bit = ref->bit;
    cycleWire_.varType = ElemType::Bool;
    hasCycleWire_ = true;
    // Published on the bus (a Modbus map's `cycle_done:`, docs/modbus.md): its tag follows the variable.
    if (TagId tag = cell_.bus.find(cell_.run.cycleDoneVar); tag != kNoTag)
      fromPlc_.push_back(slotOf(cell::makeWire(tag, plant::PortDir::In, *ref, ElemType::Bool, cell_.run.cycleDoneVar)));
  }
  trace.signals.clear();
  for (TagId id = 0; id < cell_.bus.size(); ++id) trace.signals.push_back({cell_.bus.name(id), cell_.bus.type(id), 0});
  keepChange_.assign(cell_.bus.size(), options_.keepAllChanges ? 1 : 0);
  for (TagId id = 0; id < cell_.bus.size(); ++id)
    if (std::ranges::find(options_.keptSignals, cell_.bus.name(id)) != options_.keptSignals.end()) keepChange_[id] = 1;
  if (options_.keepAllChanges) trace.changes.reserve(1 << 16);
  trace.setWindow(options_.traceWindow);
  trace.activities.reserve(1024);
}

Simulation::~Simulation() = default;

void Simulation::start() {
  started_ = true;
  if (runtime_) {
    runtime_->coldStart();
    uint8_t* mem = runtime_->machine().memory();
    if (options_.preset) options_.preset(*runtime_);
    readFromPlc(mem);
  }
  for (TagId id = 0; id < cell_.bus.size(); ++id) cell_.trace.signals[id].initial = cell_.bus.raw(id);
  cell_.bus.clearChanges();
  for (TraceSink* sink : options_.traceSinks) sink->begin(cell_.trace);
  // Paced from here: the set-up before (servers, cold start, a historian's first rows) is no
  // tick's work, so the first ticks do not start late catching up with it.
  if (paced_) paced_->resume();
}

void Simulation::recordChanges() {
  Trace& trace = cell_.trace;
  tickChanged_ = cell_.world.changes() != worldChanges_;
  worldChanges_ = cell_.world.changes();
  cell_.bus.forEachChanged([&](TagId id) {
    tickChanged_ = true;
    SignalChange c{nowNs_, id, cell_.bus.raw(id)};
    for (TraceSink* sink : options_.traceSinks) sink->change(c);
    if (keepChange_[id]) trace.changes.push_back(c);
  });
  cell_.bus.clearChanges();
}

// A fault report on one line, for tables and reports.
static std::string oneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ';');
  return text;
}

void Simulation::finish(RunEnd end, std::string message) {
  ended_ = true;
  if (runtime_ && !runtime_->exit()) {  // FB_exit, unless the PLC already faulted
    end = RunEnd::PlcFault;
    message = oneLine("FB_exit: " + runtime_->faultText());
    cell_.trace.faults.push_back({nowNs_, "PLC", message});
  }
  Trace& trace = cell_.trace;
  trace.end = end;
  trace.endMessage = std::move(message);
  trace.endNs = nowNs_;  // without a completed cycle the window stays empty: reports use the whole run
  trace.time.ticks = ticks_;
  if (paced_) {
    trace.time.paced = true;
    trace.time.lateTicks = paced_->lateTicks();
    trace.time.maxLateNs = paced_->maxLateNs();
  }
  for (auto& d : cell_.devices) d->finish(nowNs_, trace);
  for (BusBridge* b : options_.bridges) b->simulationStopped();
  for (TraceSink* sink : options_.traceSinks) sink->end(trace);
}

// A level of the cycle marker: its rising edge ends a cycle. True if that ends the run.
bool Simulation::countCycle(bool done) {
  bool ends = false;
  if (done && !lastCycleDone_) {
    Trace& trace = cell_.trace;
    trace.cycleStartNs = lastCycleEdgeNs_;
    trace.cycleEndNs = nowNs_;
    trace.cycles.push_back({lastCycleEdgeNs_, nowNs_});  // once per cycle, amortised like the activities
    lastCycleEdgeNs_ = nowNs_;
    ++trace.cyclesCompleted;
    if (trace.cyclesCompleted >= cell_.run.cycles && !cell_.run.until.valid) {
      finish(RunEnd::Completed, std::to_string(trace.cyclesCompleted) + " cycle(s) completed");
      ends = true;
    }
  }
  lastCycleDone_ = done;
  return ends;
}

// The soft PLC's stop conditions: a fault, the cycle count, `until`.
bool Simulation::checkPlcStop() {
  uint8_t* mem = runtime_->machine().memory();
  if (runtime_->state() == plc::PlcState::Fault) {
    std::string text = oneLine(runtime_->faultText());
    cell_.trace.faults.push_back({nowNs_, "PLC", text});
    finish(RunEnd::PlcFault, text);
    return true;
  }
  if (hasCycleWire_ && countCycle((mem[cycleWire_.address] >> (cycleWire_.bit >= 0 ? cycleWire_.bit : 0)) & 1)) return true;
  if (cell_.run.until.valid && cell::evaluate(cell_.run.until, mem)) {
    finish(RunEnd::Completed, "'" + cell_.run.until.text + "' became true");
    return true;
  }
  return false;
}

bool Simulation::checkStop() {
  if (runtime_ && checkPlcStop()) return true;
  if (!runtime_ && cell_.run.cycleDoneTag != kNoTag) {
    // An external PLC ran before the cell did: a marker already set at the first step is its
    // past, not an edge.
    bool done = cell_.bus.getBool(cell_.run.cycleDoneTag);
    if (!cycleTagSeen_) lastCycleDone_ = done;
    cycleTagSeen_ = true;
    if (countCycle(done)) return true;
  }
  if (cell_.run.stopOnCollision && cell_.world.collided()) {
    finish(RunEnd::Collision, "robots collided in a shared zone");
    return true;
  }
  if (cell_.run.stopOnDeviceError) {
    for (const auto& d : cell_.devices)
      if (int32_t code = d->errorCode()) {
        std::string msg = d->name() + " reported error " + std::to_string(code);
        cell_.trace.faults.push_back({nowNs_, d->name(), msg});
        finish(RunEnd::DeviceError, msg);
        return true;
      }
  }
  if (nowNs_ >= timeLimitNs_) {
    finish(RunEnd::TimeLimit, "time limit reached without meeting the stop condition");
    return true;
  }
  if (options_.interrupt && options_.interrupt->load()) {
    finish(RunEnd::Interrupted, "interrupted");
    return true;
  }
  return false;
}

void Simulation::scanPlc() {
  uint8_t* mem = runtime_->machine().memory();
  bool touched = false;
  for (const WireSlot& w : toPlc_) touched |= storeVariable(mem + w.address, w.bit, w.varType, cell_.bus, w.tag);
  uint8_t* image = runtime_->inputImage();
  for (const WireSlot& w : toInputImage_) touched |= storeVariable(image + w.address, w.bit, w.varType, cell_.bus, w.tag);
  if (touched) runtime_->inputsTouched();
  if (options_.beforeScan) options_.beforeScan(*runtime_);
  runtime_->tick();
  readFromPlc(mem);
  // After the outputs reached the bus: what afterScan publishes of the PLC and of the devices'
  // signals (serve --opcua) is one image of this scan.
  if (options_.afterScan) options_.afterScan(*runtime_);
}

void Simulation::readFromPlc(const uint8_t* mem) {
  for (const WireSlot& w : fromPlc_) loadVariable(mem + w.address, w.bit, w.varType, cell_.bus, w.tag);
}

// False if a bridge failed; the run then ends as a fault of the (external) PLC.
bool Simulation::pullBridges() {
  for (BusBridge* b : options_.bridges) {
    if (b->pull(cell_.bus, nowNs_)) continue;
    std::string msg = b->failure();
    cell_.trace.faults.push_back({nowNs_, "PLC", msg});
    finish(RunEnd::PlcFault, msg);
    return false;
  }
  return true;
}

bool Simulation::step() {
  if (ended_) return false;
  if (!started_) start();
  if (options_.control && !options_.control->beforeTick(*this)) {
    finish(RunEnd::Interrupted, options_.control->resetting() ? "reset" : "interrupted");
    return false;
  }
  int64_t baseTickNs = runtime_ ? runtime_->baseTickNs() : cell_.run.plcCycleNs;
  if (runtime_) {
    nowNs_ = runtime_->nextTickNs();
    scanPlc();
  } else {
    nowNs_ = static_cast<int64_t>(ticks_) * baseTickNs;
    clock_->advanceTo(nowNs_);
  }
  if (!pullBridges()) return false;
  plant::StepContext ctx{nowNs_, baseTickNs, cell_.bus, cell_.world, cell_.trace};
  if (recogniser_) recogniser_->observe(cell_.bus, nowNs_);
  else
    for (auto& d : cell_.devices) d->step(ctx);
  for (BusBridge* b : options_.bridges) b->push(cell_.bus, nowNs_);
  recordChanges();
  ++ticks_;
  for (TraceSink* sink : options_.traceSinks) sink->tick(cell_.trace, nowNs_);
  return !checkStop();
}

// Event-driven time. After a tick that changed no signal and no world fact, with the PLC's next
// scan a provable repeat, the ticks before the earliest device event (or the time limit) would
// each repeat the scan, step devices that change nothing, record nothing and stop on nothing
// (the stop conditions read the same PLC memory, world and device errors): they are counted as
// passed, the PLC's skipped-scan statistics and the trace sinks' tick() included, and the next
// tick runs normally at its own time. Nothing is allocated.
void Simulation::skipIdleTicks() {
  if (!jumps_ || tickChanged_ || (runtime_ && !runtime_->scanWouldRepeat())) return;
  int64_t eventNs = timeLimitNs_;
  for (const auto& d : cell_.devices) eventNs = std::min(eventNs, d->nextEventNs());
  const int64_t baseTickNs = runtime_ ? runtime_->baseTickNs() : cell_.run.plcCycleNs;
  if (baseTickNs <= 0) return;
  eventNs = std::min(eventNs, INT64_MAX - baseTickNs);  // a run without end nor event: no overflow
  if (eventNs <= nowNs_) return;
  // The first tick at or after the event must run: ticks before it are skipped.
  const uint64_t eventTick = static_cast<uint64_t>(eventNs / baseTickNs + (eventNs % baseTickNs != 0));
  const uint64_t nextTick = runtime_ ? runtime_->ticks() : ticks_;
  if (eventTick <= nextTick) return;
  const uint64_t count = eventTick - nextTick;
  if (!options_.traceSinks.empty())
    for (uint64_t t = nextTick; t < eventTick; ++t)
      for (TraceSink* sink : options_.traceSinks) sink->tick(cell_.trace, static_cast<int64_t>(t) * baseTickNs);
  if (runtime_) runtime_->skipRepeatedTicks(count);
  ticks_ += count;
  cell_.trace.time.ticksSkipped += count;
  ++cell_.trace.time.jumps;
}

RunEnd Simulation::run() {
  while (step()) skipIdleTicks();
  return cell_.trace.end;
}

}  // namespace virtcom::sim
