#include "hmi/request.hpp"

#include <charconv>
#include <cmath>
#include <optional>

#include <nlohmann/json.hpp>

namespace virtcom::hmi {

namespace {

using Json = nlohmann::json;

std::string queryValue(const Request& r, const char* key) {
  for (const auto& [k, v] : r.query)
    if (k == key) return v;
  return {};
}

ParsedRequest failed(int status, const std::string& message) {
  ParsedRequest p;
  p.error = errorResponse(status, message);
  return p;
}

// Compares in time independent of where the texts differ, so the token cannot be guessed a
// character at a time from response times.
bool sameSecret(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  unsigned char diff = 0;
  for (size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned char>(a[i] ^ b[i]);
  return diff == 0;
}

// Nothing if the request may write; else the refusal.
std::optional<ParsedRequest> refusal(const Request& r, const WriteAccess& access) {
  if (access.readOnly) return failed(403, "the HMI is read-only (--hmi-readonly)");
  if (access.token.empty()) return std::nullopt;
  static constexpr std::string_view kBearer = "Bearer ";
  if (r.authorization.compare(0, kBearer.size(), kBearer) != 0 ||
      !sameSecret(r.authorization.substr(kBearer.size()), access.token))
    return failed(401, "writing needs the HMI token: 'Authorization: Bearer TOKEN' (printed at start-up, or --hmi-token)");
  return std::nullopt;
}

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> items;
  size_t start = 0;
  while (start <= text.size()) {
    size_t comma = text.find(',', start);
    if (comma == std::string::npos) comma = text.size();
    if (comma > start) items.push_back(text.substr(start, comma - start));
    start = comma + 1;
  }
  return items;
}

// A string member of the body: absent or not a string gives `missing` (true) and "".
std::string stringMember(const Json& body, const char* key, bool& missing) {
  auto it = body.find(key);
  if (it == body.end() || !it->is_string()) {
    missing = true;
    return {};
  }
  return it->get<std::string>();
}

ParsedRequest parseControl(const Json& body) {
  bool missing = false;
  std::string action = stringMember(body, "action", missing);
  ParsedRequest p;
  p.route = Route::Control;
  if (action == "pause") p.action = Action::Pause;
  else if (action == "run") p.action = Action::Run;
  else if (action == "reset") p.action = Action::Reset;
  else if (action == "step" || action == "speed") {
    p.action = action == "step" ? Action::Step : Action::Speed;
    auto it = body.find("value");
    p.value = 1;
    if (it != body.end()) {
      if (!it->is_number()) return failed(400, "'value' must be a number");
      p.value = it->get<double>();
    }
    if (p.action == Action::Speed && !(std::isfinite(p.value) && p.value >= 0.01 && p.value <= 1000))
      return failed(400, "the speed factor must be between 0.01 and 1000");
    if (p.action == Action::Step && !(p.value >= 1 && p.value <= 100000))
      return failed(400, "the step count must be between 1 and 100000");
    if (p.action == Action::Step) p.value = std::floor(p.value);
  } else {
    return failed(400, "'action' must be one of pause, run, step, speed, reset");
  }
  return p;
}

ParsedRequest parseWrite(const Json& body) {
  bool missing = false;
  ParsedRequest p;
  p.route = Route::Write;
  p.name = stringMember(body, "name", missing);
  p.text = stringMember(body, "value", missing);
  if (missing) return failed(400, "a write needs 'name' and 'value' (IEC text, e.g. \"TRUE\", \"42\", \"T#1s\")");
  if (p.name.empty() || p.name.size() > kMaxText || p.text.size() > kMaxText) return failed(400, "'name' or 'value' is empty or too long");
  auto force = body.find("force");
  if (force != body.end()) {
    if (!force->is_boolean()) return failed(400, "'force' must be true or false");
    p.force = force->get<bool>();
  }
  return p;
}

ParsedRequest parseRelease(const Json& body) {
  ParsedRequest p;
  p.route = Route::Release;
  auto it = body.find("name");
  if (it == body.end()) return p;  // release all
  if (!it->is_string() || it->get<std::string>().size() > kMaxText) return failed(400, "'name' must be a variable name");
  p.name = it->get<std::string>();
  return p;
}

ParsedRequest parseFault(const Json& body) {
  bool missing = false;
  ParsedRequest p;
  p.route = Route::Fault;
  p.name = stringMember(body, "device", missing);
  auto code = body.find("code");
  if (missing || code == body.end() || !code->is_number_integer())
    return failed(400, "a fault needs 'device' (its name) and 'code' (an integer error code, 0 clears)");
  int64_t value = code->get<int64_t>();
  if (value < 0 || value > 32767) return failed(400, "'code' must be between 0 and 32767 (the device's INT error output)");
  p.code = static_cast<int32_t>(value);
  return p;
}

ParsedRequest parsePost(const Request& r, const WriteAccess& access) {
  using Parser = ParsedRequest (*)(const Json&);
  static constexpr std::pair<std::string_view, Parser> kPosts[] = {
      {"/api/control", parseControl}, {"/api/write", parseWrite}, {"/api/release", parseRelease}, {"/api/fault", parseFault}};
  for (const auto& [path, parse] : kPosts) {
    if (r.path != path) continue;
    if (auto refused = refusal(r, access)) return *refused;
    Json body = r.body.empty() ? Json::object() : Json::parse(r.body, nullptr, false);
    if (body.is_discarded() || !body.is_object()) return failed(400, "the body must be a JSON object");
    return parse(body);
  }
  return failed(404, "no such API: POST " + r.path.substr(0, kMaxText));
}

bool hasQuery(const Request& r, const char* key) {
  for (const auto& [k, v] : r.query)
    if (k == key) return true;
  return false;
}

// ?key= as a whole number in [min, max] into `value` (kept when absent and not `required`);
// the refusal otherwise.
std::optional<ParsedRequest> integerParameter(const Request& r, const char* key, int64_t min, int64_t max, bool required,
                                              int64_t& value) {
  if (!hasQuery(r, key)) {
    if (!required) return std::nullopt;
    return failed(400, std::string("'") + key + "' is missing: give ?" + key + "=N");
  }
  const std::string text = queryValue(r, key);
  int64_t parsed = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), parsed);
  if (ec != std::errc() || end != text.data() + text.size() || parsed < min || parsed > max)
    return failed(400, std::string("'") + key + "' must be a whole number from " + std::to_string(min) + " to " + std::to_string(max) +
                           ", not '" + text.substr(0, 40) + "'");
  value = parsed;
  return std::nullopt;
}

// GET /api/history/range and /api/history/state: the run, the times (virtual ns), the signals.
ParsedRequest parseHistory(const Request& r, Route route) {
  ParsedRequest p;
  p.route = route;
  int64_t points = p.points;
  if (auto refused = integerParameter(r, "run", 1, INT64_MAX, true, p.run)) return *refused;
  if (route == Route::HistoryState) {
    if (auto refused = integerParameter(r, "at", 0, INT64_MAX, true, p.fromNs)) return *refused;
    return p;
  }
  if (auto refused = integerParameter(r, "from", 0, INT64_MAX, false, p.fromNs)) return *refused;
  if (auto refused = integerParameter(r, "to", 0, INT64_MAX, false, p.toNs)) return *refused;
  if (auto refused = integerParameter(r, "points", kMinPoints, kMaxPoints, false, points)) return *refused;
  p.points = static_cast<int32_t>(points);
  if (p.fromNs > p.toNs) return failed(400, "'from' (" + std::to_string(p.fromNs) + " ns) is after 'to' (" + std::to_string(p.toNs) + " ns)");
  p.signals = splitList(queryValue(r, "signals"));
  if (p.signals.size() > kMaxWatch) return failed(400, "at most " + std::to_string(kMaxWatch) + " signals per request");
  for (const std::string& name : p.signals)
    if (name.size() > kMaxText) return failed(400, "a signal name is longer than " + std::to_string(kMaxText) + " characters");
  return p;
}

ParsedRequest parseGet(const Request& r) {
  ParsedRequest p;
  if (r.path == "/api/history/runs") {
    p.route = Route::HistoryRuns;
  } else if (r.path == "/api/history/range") {
    return parseHistory(r, Route::HistoryRange);
  } else if (r.path == "/api/history/state") {
    return parseHistory(r, Route::HistoryState);
  } else if (r.path == "/api/model") {
    p.route = Route::Model;
  } else if (r.path == "/api/stream") {
    p.route = Route::Stream;
    p.watch = splitList(queryValue(r, "watch"));
    if (p.watch.size() > kMaxWatch) return failed(400, "at most " + std::to_string(kMaxWatch) + " watched variables per stream");
  } else if (r.path == "/api/vars") {
    p.route = Route::Vars;
    p.match = queryValue(r, "match").substr(0, kMaxText);
  } else if (r.path.rfind("/api/", 0) == 0) {
    return failed(404, "no such API: GET " + r.path.substr(0, kMaxText));
  } else {
    p.route = Route::Asset;
    std::string_view asset = r.path;
    if (!asset.empty() && asset.front() == '/') asset.remove_prefix(1);
    p.asset = asset.empty() ? "index.html" : std::string(asset.substr(0, kMaxText));
  }
  return p;
}

}  // namespace

Response errorResponse(int status, const std::string& message) {
  Response r;
  r.status = status;
  r.body = Json{{"error", message}}.dump(-1, ' ', false, Json::error_handler_t::replace);
  return r;
}

ParsedRequest parseRequest(const Request& request, const WriteAccess& access) {
  if (request.method == "GET" || request.method == "HEAD") return parseGet(request);
  if (request.method == "POST") return parsePost(request, access);
  return failed(405, "only GET and POST are served");
}

}  // namespace virtcom::hmi
