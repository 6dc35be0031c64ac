#pragma once
// The HMI's answers, without sockets: a checked request (request.hpp) in, a response out, over
// the running cell's LiveState. The stream is the one route that is not a single response:
// openStream() gives the session whose frames the HTTP layer sends.
#include <memory>

#include <nlohmann/json.hpp>

#include "cell/cell.hpp"
#include "hmi/history_api.hpp"
#include "hmi/live_state.hpp"
#include "hmi/request.hpp"
#include "hmi/stream_session.hpp"
#include "hmi/variable_catalog.hpp"
#include "lang/sfc/step_monitor.hpp"

namespace virtcom::hmi {

// An activity-diagram rule as the rule panel lists it (the CLI finds them with their fired
// flags, which it gives LiveState::watchRules in the same order).
struct RuleInfo {
  std::string diagram, index, luType, then;
};

class Api {
 public:
  // `live` and the cell's PLC module must outlive the Api (a reset keeps the module object:
  // LiveState::restart); the devices must be prepared (see cellModel()).
  Api(const cell::Cell& cell, LiveState& live, int64_t baseTickNs, WriteAccess access, std::vector<RuleInfo> rules = {});

  // Before serving: reset answers 409 with `why` (e.g. an attached protocol server holds the
  // PLC image); without it, reset is posted to the live state.
  void refuseReset(std::string why) { resetRefusal_ = std::move(why); }

  // Before serving: the history routes answer from `history` (which must outlive the Api) and
  // the model says so ("history": true); `replay` (virtcom history --http): there is no live
  // run, the page only browses the history ("replay": true). Without it they answer 404.
  void attachHistory(HistoryApi& history, bool replay);

  // The SFC panel's steps, when they are not the cell's soft PLC's (virtcom monitor: the real
  // PLC's, mirrored into the live state's memory; see LiveState::mirrorMemory).
  void showSteps(std::vector<sfc::StepVariable> steps);

  const WriteAccess& access() const { return access_; }
  // Any route but Route::Stream. Thread-safe (HTTP threads call it at once). `client`: who asks,
  // as a write or force it makes is audited (LiveState::auditWrites).
  Response handle(const ParsedRequest& request, const ExternalWriter& client = ExternalWriter{WriteProtocol::Http});
  // Route::Stream: a new viewer's session.
  std::unique_ptr<StreamSession> openStream(const ParsedRequest& request) const;

 private:
  Response asset(const std::string& path) const;
  Response model() const;
  Response vars(const std::string& match) const;
  Response control(const ParsedRequest& r);
  Response write(const ParsedRequest& r, const ExternalWriter& client);
  Response fault(const ParsedRequest& r);

  std::vector<std::string> deviceNames_;
  LiveState& live_;
  WriteAccess access_;
  nlohmann::json model_;
  VariableCatalog catalog_;
  std::vector<ElemType> tagTypes_;
  std::vector<sfc::StepVariable> steps_;  // the SFC panel's steps, in declaration order
  std::string resetRefusal_;
  HistoryApi* history_ = nullptr;
};

}  // namespace virtcom::hmi
