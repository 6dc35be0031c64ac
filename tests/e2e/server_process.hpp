#pragma once
// A `virtcom` server process for e2e tests: started with its stderr on a pipe, its listening
// port read from the announcement it prints ("<prefix>127.0.0.1:PORT"), stopped with SIGTERM.
// Every wait has a deadline, so a broken server fails a test instead of hanging it.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "support/eventually.hpp"

namespace virtcom::e2e {

class ServerProcess {
 public:
  static constexpr auto kDeadline = test::kDeadline;  // generous: sanitizer builds start slowly

  // Runs `exe args...` in `dir`. Check started() / port().
  ServerProcess(const std::string& exe, std::vector<std::string> args, const std::string& dir,
                const std::string& announcePrefix) {
    int errPipe[2];
    if (::pipe2(errPipe, O_CLOEXEC) != 0) return;
    args.insert(args.begin(), exe);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_ = ::fork();
    if (pid_ == 0) {  // child: only async-signal-safe calls
      int in = ::open("/dev/null", O_RDONLY);
      if (in < 0 || ::chdir(dir.c_str()) != 0) ::_exit(125);
      ::dup2(in, 0);
      ::dup2(errPipe[1], 2);
      ::execv(exe.c_str(), argv.data());
      ::_exit(127);
    }
    ::close(errPipe[1]);
    errFd_ = errPipe[0];
    if (pid_ > 0) port_ = waitForPort(announcePrefix);
  }
  ~ServerProcess() {
    if (pid_ > 0) stop();
    if (errFd_ >= 0) ::close(errFd_);
  }
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;

  // The announced port, 0 if none came before the deadline or the process ended.
  int port() const { return port_; }
  // What the process wrote to stderr so far.
  const std::string& errorOutput() const { return err_; }
  // Reads stderr until `text` has appeared; false if the deadline passed or the process ended.
  bool waitFor(const std::string& text) {
    auto until = std::chrono::steady_clock::now() + kDeadline;
    while (err_.find(text) == std::string::npos) {
      if (std::chrono::steady_clock::now() >= until || !drainStderr(100)) return false;
    }
    return true;
  }

  // Waits until `text` has been written `count` times; false at the deadline or the process's end.
  bool waitForCount(const std::string& text, size_t count) {
    auto until = std::chrono::steady_clock::now() + kDeadline;
    auto seen = [&] {
      size_t n = 0;
      for (size_t at = err_.find(text); at != std::string::npos; at = err_.find(text, at + 1)) ++n;
      return n;
    };
    while (seen() < count) {
      if (std::chrono::steady_clock::now() >= until || !drainStderr(100)) return false;
    }
    return true;
  }

  // SIGTERM, then the exit status: 128 + signal if killed by one, -1 (after SIGKILL) if it hangs.
  int stop() { return signal(SIGTERM); }
  // Sends `sig` (SIGKILL: a crash the process cannot clean up after), then the exit status as stop().
  int signal(int sig) {
    ::kill(pid_, sig);
    return waitExit();
  }
  int waitExit() {
    auto until = std::chrono::steady_clock::now() + kDeadline;
    int status = 0;
    while (std::chrono::steady_clock::now() < until) {
      drainStderr(0);
      pid_t r = ::waitpid(pid_, &status, WNOHANG);
      if (r == pid_) {
        pid_ = -1;
        drainStderr(0);
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
    return -1;
  }

 private:
  // Appends what stderr has; false once it is closed.
  bool drainStderr(int timeoutMs) {
    pollfd p{errFd_, POLLIN, 0};
    if (::poll(&p, 1, timeoutMs) <= 0) return true;
    char buf[512];
    ssize_t n = ::read(errFd_, buf, sizeof buf);
    if (n <= 0) return false;
    err_.append(buf, static_cast<size_t>(n));
    return true;
  }

  int waitForPort(const std::string& prefix) {
    const std::string announce = prefix + "127.0.0.1:";
    auto until = std::chrono::steady_clock::now() + kDeadline;
    while (std::chrono::steady_clock::now() < until) {
      if (!drainStderr(100)) return 0;
      auto at = err_.find(announce);
      if (at != std::string::npos && err_.find_first_of(" \n", at + announce.size()) != std::string::npos)
        return std::atoi(err_.c_str() + at + announce.size());
    }
    return 0;
  }

  pid_t pid_ = -1;
  int errFd_ = -1;
  int port_ = 0;
  std::string err_;
};

// A port that was free a moment ago: the server `start()` returns announced it and was stopped,
// so nothing listens there any more. 0 if it did not start or did not stop cleanly.
template <class Start>
int portClosedAfter(Start start) {
  auto server = start();
  const int port = server->port();
  return server->stop() == 0 ? port : 0;
}

}  // namespace virtcom::e2e
