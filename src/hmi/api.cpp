#include "hmi/api.hpp"

#include <algorithm>

#include "core/ascii.hpp"
#include "hmi/assets.hpp"
#include "hmi/cell_model.hpp"

namespace virtcom::hmi {

namespace {

using Json = nlohmann::json;

constexpr size_t kMaxVarsListed = 200;

Response ok(const Json& body = Json{{"ok", true}}) {
  Response r;
  r.body = body.dump(-1, ' ', false, Json::error_handler_t::replace);
  return r;
}

bool isForced(const Snapshot& s, const std::string& name) {
  return std::ranges::any_of(s.forced, [&](const std::string& f) { return iequalsAscii(f, name); });
}

}  // namespace

Api::Api(const cell::Cell& cell, LiveState& live, int64_t baseTickNs, WriteAccess access, std::vector<RuleInfo> rules)
    : live_(live), access_(std::move(access)), model_(cellModel(cell, baseTickNs)), catalog_(cell.module.get()) {
  for (const auto& d : cell.devices) deviceNames_.push_back(d->name());
  for (TagId id = 0; id < cell.bus.size(); ++id) tagTypes_.push_back(cell.bus.type(id));
  showSteps(cell.module ? sfc::findSteps(*cell.module) : std::vector<sfc::StepVariable>{});
  Json ruleList = Json::array();
  for (const RuleInfo& r : rules)
    ruleList.push_back({{"diagram", r.diagram}, {"index", r.index}, {"luType", r.luType}, {"then", r.then}});
  model_["rules"] = std::move(ruleList);
  model_["readOnly"] = access_.readOnly;
  model_["tokenRequired"] = !access_.readOnly && !access_.token.empty();
  model_["history"] = false;
  model_["replay"] = false;
}

void Api::showSteps(std::vector<sfc::StepVariable> steps) {
  steps_ = std::move(steps);
  Json paths = Json::array();
  for (const sfc::StepVariable& step : steps_) paths.push_back(step.path);
  model_["sfcSteps"] = std::move(paths);
}

void Api::attachHistory(HistoryApi& history, bool replay) {
  history_ = &history;
  model_["history"] = true;
  model_["replay"] = replay;
}

Response Api::handle(const ParsedRequest& r, const ExternalWriter& client) {
  switch (r.route) {
    case Route::Asset: return asset(r.asset);
    case Route::Model: return model();
    case Route::Vars: return vars(r.match);
    case Route::Control: return control(r);
    case Route::Write: return write(r, client);
    case Route::Release: {
      Command c;
      c.kind = Command::Kind::Release;
      c.name = r.name;
      live_.post(std::move(c));
      return ok();
    }
    case Route::Fault: return fault(r);
    case Route::HistoryRuns:
    case Route::HistoryRange:
    case Route::HistoryState:
      if (!history_) return errorResponse(404, "this HMI keeps no history: start it with --history FILE, or browse a file with virtcom history FILE --http");
      return history_->handle(r);
    case Route::Stream: return errorResponse(500, "the stream is served by openStream()");
    case Route::Error: return r.error;
  }
  return errorResponse(500, "unknown route");
}

std::unique_ptr<StreamSession> Api::openStream(const ParsedRequest& request) const {
  return std::make_unique<StreamSession>(live_, catalog_, tagTypes_, steps_, request.watch);
}

Response Api::asset(const std::string& path) const {
  const Asset* a = findAsset(path);
  if (!a) return errorResponse(404, "no such page: /" + path.substr(0, kMaxText));
  Response r;
  r.contentType = std::string(a->contentType);
  r.body = std::string(a->body);
  return r;
}

Response Api::model() const {
  Json m = model_;
  live_.read([&](const Snapshot& s) {
    m["paused"] = s.paused;
    m["speed"] = s.speed;
    m["lateTicks"] = s.lateTicks;
  });
  return ok(m);
}

Response Api::vars(const std::string& match) const {
  Json list = Json::array();
  auto found = catalog_.search(match, kMaxVarsListed);
  live_.read([&](const Snapshot& s) {
    for (const CatalogVariable* v : found)
      list.push_back({{"name", v->name},
                      {"type", catalog_.typeName(v->ref)},
                      {"value", s.memory.empty() ? "" : bc::formatValue(*catalog_.module(), v->ref, s.memory.data())},
                      {"readOnly", v->ref.readOnly},
                      {"forced", isForced(s, v->name)}});
  });
  return ok(Json{{"vars", list}, {"more", found.size() >= kMaxVarsListed}});
}

Response Api::control(const ParsedRequest& r) {
  Command c;
  switch (r.action) {
    case Action::Pause: c.kind = Command::Kind::Pause; break;
    case Action::Run: c.kind = Command::Kind::Run; break;
    case Action::Step: c.kind = Command::Kind::Step; break;
    case Action::Speed: c.kind = Command::Kind::Speed; break;
    case Action::Reset:
      if (!resetRefusal_.empty()) return errorResponse(409, resetRefusal_);
      c.kind = Command::Kind::Reset;
      break;
  }
  c.value = r.value;
  live_.post(std::move(c));
  return ok();
}

Response Api::write(const ParsedRequest& r, const ExternalWriter& client) {
  if (!catalog_.module()) return errorResponse(409, "the cell has no soft PLC: there are no variables to write");
  auto ref = catalog_.find(r.name);
  if (!ref) return errorResponse(404, "unknown variable '" + r.name + "' (use the qualified name, e.g. MAIN.count or GVL.x)");
  if (ref->readOnly) return errorResponse(400, "'" + r.name + "' is a CONSTANT and cannot be written");
  const bc::TypeDesc& type = catalog_.module()->types[ref->type];
  if (type.kind == bc::TypeKind::Struct || type.kind == bc::TypeKind::Array)
    return errorResponse(400, "'" + r.name + "' is a " + type.name + ": write its elements one by one");
  // Parsed here, into a scratch buffer holding the variable just past the null guard (the lowest
  // address a variable may have), so the simulation's thread only copies bytes.
  const uint32_t size = std::max<uint32_t>(type.size, 1);
  std::vector<uint8_t> scratch(bc::Module::kNullGuard + size, 0);
  bc::VarRef rebased = *ref;
  rebased.address = bc::Module::kNullGuard;
  std::string problem = bc::writeValueFromText(*catalog_.module(), rebased, r.text, scratch.data());
  if (!problem.empty()) return errorResponse(400, r.name + ": " + problem);
  Command c;
  c.kind = Command::Kind::Write;
  c.ref = *ref;
  c.bytes.assign(scratch.begin() + bc::Module::kNullGuard, scratch.end());
  c.name = r.name;
  c.force = r.force;
  c.writer = client;
  c.writer.force = r.force;
  live_.post(std::move(c));
  return ok();
}

Response Api::fault(const ParsedRequest& r) {
  for (uint32_t i = 0; i < deviceNames_.size(); ++i) {
    if (!iequalsAscii(deviceNames_[i], r.name)) continue;
    Command c;
    c.kind = Command::Kind::Fault;
    c.device = i;
    c.code = r.code;
    live_.post(std::move(c));
    return ok();
  }
  return errorResponse(404, "no device named '" + r.name + "'");
}

}  // namespace virtcom::hmi
