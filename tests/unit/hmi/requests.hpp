#pragma once
// HTTP requests as the HMI's server hands them over (hmi/request.hpp), for the tests: the fields
// a test leaves out stay empty (no client address: not audited as a peer).
#include <string>
#include <utility>
#include <vector>

#include "hmi/request.hpp"

namespace virtcom::hmi::test {

inline Request request(std::string method, std::string path, std::vector<std::pair<std::string, std::string>> query = {},
                       std::string body = "", std::string authorization = "") {
  Request r;
  r.method = std::move(method);
  r.path = std::move(path);
  r.query = std::move(query);
  r.body = std::move(body);
  r.authorization = std::move(authorization);
  return r;
}
inline Request get(std::string path, std::vector<std::pair<std::string, std::string>> query = {}) {
  return request("GET", std::move(path), std::move(query));
}
inline Request post(std::string path, std::string body, std::string authorization = "") {
  return request("POST", std::move(path), {}, std::move(body), std::move(authorization));
}

}  // namespace virtcom::hmi::test
