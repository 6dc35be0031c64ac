#pragma once
// The HMI's answers, without sockets: a checked request (request.hpp) in, a response out, over
// the running cell's LiveState. The stream is the one route that is not a single response:
// openStream() gives the session whose frames the HTTP layer sends.
#include <memory>

#include <nlohmann/json.hpp>

#include "cell/cell.hpp"
#include "hmi/live_state.hpp"
#include "hmi/request.hpp"
#include "hmi/stream_session.hpp"
#include "hmi/variable_catalog.hpp"

namespace virtcom::hmi {

class Api {
 public:
  // `cell` and `live` must outlive the Api; the devices must be prepared (see cellModel()).
  Api(const cell::Cell& cell, LiveState& live, int64_t baseTickNs, WriteAccess access);

  const WriteAccess& access() const { return access_; }
  // Any route but Route::Stream. Thread-safe (HTTP threads call it at once).
  Response handle(const ParsedRequest& request);
  // Route::Stream: a new viewer's session.
  std::unique_ptr<StreamSession> openStream(const ParsedRequest& request) const;

 private:
  Response asset(const std::string& path) const;
  Response model() const;
  Response vars(const std::string& match) const;
  Response control(const ParsedRequest& r);
  Response write(const ParsedRequest& r);
  Response fault(const ParsedRequest& r);

  const cell::Cell& cell_;
  LiveState& live_;
  WriteAccess access_;
  nlohmann::json model_;
  VariableCatalog catalog_;
  std::vector<ElemType> tagTypes_;
};

}  // namespace virtcom::hmi
