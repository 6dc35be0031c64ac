#pragma once
// The HMI's HTTP requests as data, without sockets: what a request asks for (parseRequest) and
// the response it gets. The routes, their bodies and the write permission are decided here, so
// that every untrusted byte of a request is checked by one pure function (unit-tested and
// fuzzed, tests/fuzz/fuzz_hmi_request.cpp); docs/hmi.md is the API's documentation.
// Compiled by the clang-19 fuzz build too (tests/fuzz/fuzz_hmi_request.cpp).
#include <cstdint>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace virtcom::hmi {

struct Request {
  std::string method;   // "GET", "POST", ...
  std::string path;     // without the query: "/api/model"
  std::vector<std::pair<std::string, std::string>> query;  // decoded
  std::string body;
  std::string authorization;  // the Authorization header, empty if none
};

struct Response {
  int status = 200;
  std::string contentType = "application/json";
  std::string body;
};

// Who may change the running cell: nobody (--hmi-readonly), anyone who can connect (loopback
// without --hmi-token), or the holder of the token ("Authorization: Bearer TOKEN").
struct WriteAccess {
  bool readOnly = false;
  std::string token;  // empty: no token needed
};

enum class Route : uint8_t { Asset, Model, Stream, Vars, Control, Write, Release, Fault, HistoryRuns, HistoryRange, HistoryState, Error };

// A control action of POST /api/control.
enum class Action : uint8_t { Pause, Run, Step, Speed, Reset };

// The plot points per signal a history range asks for (?points=): the default and the bounds.
inline constexpr int32_t kDefaultPoints = 1000;
inline constexpr int32_t kMinPoints = 3;
inline constexpr int32_t kMaxPoints = 20000;

// What a request asks for, checked. Fields beyond `route` are those its route uses.
struct ParsedRequest {
  Route route = Route::Error;
  Response error;                    // Route::Error: the response to send
  std::string asset;                 // Asset: the asset path ("/" -> "index.html")
  std::vector<std::string> watch;    // Stream: ?watch=a,b (PLC variable names)
  std::string match;                 // Vars: ?match=text
  Action action = Action::Pause;     // Control
  double value = 0;                  // Control speed: the factor; Step: the tick count (>= 1)
  std::string name;                  // Write/Release: the variable (Release: empty = all); Fault: the device
  std::string text;                  // Write: the value as IEC text
  bool force = false;                // Write: keep the value over every scan until released
  int32_t code = 0;                  // Fault: the error code to inject (0 clears)
  int64_t run = 0;                   // HistoryRange/HistoryState: ?run= (>= 1)
  int64_t fromNs = 0;                // HistoryRange: ?from= (virtual ns); HistoryState: ?at=
  int64_t toNs = INT64_MAX;          // HistoryRange: ?to= (>= from)
  std::vector<std::string> signals;  // HistoryRange: ?signals=a,b (names, at most kMaxWatch)
  int32_t points = kDefaultPoints;   // HistoryRange: ?points= (per signal, kMinPoints..kMaxPoints)
};

// Reads a request. Never throws; malformed input gives Route::Error with a 4xx response whose
// JSON body says what is wrong ({"error": "..."}). Writes (POST) are checked against `access`:
// 403 when read-only, 401 without the right bearer token.
ParsedRequest parseRequest(const Request& request, const WriteAccess& access);

// {"error": message} with `status`.
Response errorResponse(int status, const std::string& message);

// The most watched variables a stream may ask for, and the longest name or value text taken.
inline constexpr size_t kMaxWatch = 64;
inline constexpr size_t kMaxText = 256;

}  // namespace virtcom::hmi
