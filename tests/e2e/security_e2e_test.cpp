// The one peer policy as a user meets it (docs/security.md): every server of `exec` and `serve`
// refuses to start beyond loopback without an allow-list or --allow-any-peer, says how, and
// lists the policy options in --help. Nothing here binds beyond loopback: a refused start binds
// nothing.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "shell_command.hpp"

namespace {

using ::testing::HasSubstr;
using virtcom::e2e::shell;

const std::string kExe = VIRTCOM_EXE;
const std::string kDataDir = VIRTCOM_E2E_DATA;
constexpr int kUsage = 64;  // src/cli/exit_codes.def

int virtcom(const std::string& args, std::string& out) { return shell("cd " + kDataDir + " && " + kExe + " " + args, out); }

TEST(SecurityE2e, EveryServerBeyondLoopbackNeedsAnAllowList) {
  struct Case {
    std::string args, listenFlag, allowFlag;
  };
  for (const Case& c : {Case{"exec counter.st --modbus 0.0.0.0:0", "--modbus", "--modbus-allow"},
                        Case{"exec counter.st --ads 0.0.0.0:0 --ads-discovery off", "--ads", "--ads-allow"},
                        Case{"serve cells/many_presses.yaml --http 0.0.0.0:0", "--http", "--http-allow"}}) {
    std::string out;
    EXPECT_EQ(virtcom(c.args, out), kUsage) << c.args << "\n" << out;
    EXPECT_THAT(out, HasSubstr("error: " + c.listenFlag + ": 0.0.0.0 is reachable beyond this machine: name the peers allowed with " +
                               c.allowFlag + " ADDRESS[/BITS],... (or let every peer in with --allow-any-peer), or bind 127.0.0.1"))
        << c.args;
  }
}

TEST(SecurityE2e, ABadAllowListNamesTheOptionAndTheItem) {
  std::string out;
  EXPECT_EQ(virtcom("exec counter.st --modbus 127.0.0.1:0 --modbus-allow 10.0.0.1/8", out), kUsage) << out;
  EXPECT_THAT(out, HasSubstr("--modbus-allow: '10.0.0.1/8' has host bits set: the network is 10.0.0.0/8"));
  out.clear();
  EXPECT_EQ(virtcom("exec counter.st --ads 127.0.0.1:0 --ads-allow 10.0.0.0/99", out), kUsage) << out;
  EXPECT_THAT(out, HasSubstr("--ads-allow: '99' is not a prefix length (0-32) in 10.0.0.0/99"));
}

TEST(SecurityE2e, ExecAndServeListThePolicyOptions) {
  for (const char* command : {"exec", "serve"}) {
    std::string out;
    ASSERT_EQ(virtcom(std::string(command) + " --help", out), 0) << out;
    for (const char* option : {"--allow-any-peer", "--max-clients", "--max-clients-per-peer", "--max-request-rate", "--modbus-allow",
                               "--modbus-readonly", "--ads-allow", "--ads-readonly"})
      EXPECT_THAT(out, HasSubstr(option)) << command;
  }
}

}  // namespace
