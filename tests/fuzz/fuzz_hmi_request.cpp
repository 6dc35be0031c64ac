// libFuzzer target for the web HMI's request layer (src/hmi/request.cpp), which reads every
// untrusted byte of an HTTP request: the input is cut into method selector, path, query,
// Authorization and body, and read under each write access. Finds crashes, hangs and
// responses that break the layer's contract (a refusal without a 4xx status and a JSON body, a
// history range outside the bounds the history answers rely on).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "hmi/request.hpp"

namespace hmi = virtcom::hmi;

namespace {

// The next '\n'-terminated field of `rest` (all of it if there is no '\n').
std::string field(std::string_view& rest) {
  size_t end = rest.find('\n');
  std::string out(rest.substr(0, end));
  rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 1);
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  static const char* const kMethods[] = {"GET", "POST", "HEAD", "PUT", "DELETE", ""};
  hmi::Request request;
  request.method = kMethods[data[0] % 6];
  std::string_view rest(reinterpret_cast<const char*>(data) + 1, size - 1);
  request.path = field(rest);
  std::string query = field(rest);
  for (size_t start = 0; start <= query.size();) {
    size_t amp = query.find('&', start);
    std::string pair = query.substr(start, amp == std::string::npos ? std::string::npos : amp - start);
    size_t eq = pair.find('=');
    request.query.emplace_back(pair.substr(0, eq), eq == std::string::npos ? "" : pair.substr(eq + 1));
    if (amp == std::string::npos) break;
    start = amp + 1;
  }
  request.authorization = field(rest);
  request.body = std::string(rest);
  for (const hmi::WriteAccess& access : {hmi::WriteAccess{}, hmi::WriteAccess{true, ""}, hmi::WriteAccess{false, "token"}}) {
    hmi::ParsedRequest parsed = hmi::parseRequest(request, access);
    if (parsed.route == hmi::Route::Error && (parsed.error.status < 400 || parsed.error.status >= 500 || parsed.error.body.empty()))
      __builtin_trap();
    if (parsed.route == hmi::Route::Stream && parsed.watch.size() > hmi::kMaxWatch) __builtin_trap();
    if (parsed.route == hmi::Route::HistoryRange &&
        (parsed.run < 1 || parsed.fromNs < 0 || parsed.fromNs > parsed.toNs || parsed.signals.size() > hmi::kMaxWatch ||
         parsed.points < hmi::kMinPoints || parsed.points > hmi::kMaxPoints))
      __builtin_trap();
  }
  return 0;
}
