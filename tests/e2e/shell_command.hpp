#pragma once
// Runs a shell command for the e2e tests (e.g. mbpoll, or a `virtcom run` that ends by itself).
#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace virtcom::e2e {

// The command's exit status (-1 if it could not run or was killed), stdout and stderr in `out`.
inline int shell(const std::string& command, std::string& out) {
  FILE* p = ::popen((command + " 2>&1").c_str(), "r");
  if (!p) return -1;
  char buf[512];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  int status = ::pclose(p);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace virtcom::e2e
