// The peer policy every server shares (docs/security.md): the loopback rule, allow-lists with
// networks, the connection limits and the request budget.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "proto/net/peer_policy.hpp"

namespace virtcom::proto::net {
namespace {

PeerOptions modbusOptions(std::string_view allow, bool anyPeer = false) {
  return PeerOptions{"modbus", "--modbus", "--modbus-allow", allow, anyPeer, false, {}};
}

TEST(PeerPolicyRule, LoopbackNeedsNoAllowList) {
  auto policy = makePeerPolicy(Endpoint{0x7f000001, 502}, modbusOptions(""));
  ASSERT_TRUE(policy) << policy.error();
  EXPECT_TRUE(policy->allows(0x7f000001));
}

TEST(PeerPolicyRule, BeyondLoopbackWithoutAnAllowListIsRefusedWithHowToFixIt) {
  auto policy = makePeerPolicy(Endpoint{0, 502}, modbusOptions(""));
  ASSERT_FALSE(policy);
  EXPECT_EQ(policy.error(),
            "--modbus: 0.0.0.0 is reachable beyond this machine: name the peers allowed with --modbus-allow ADDRESS[/BITS],... "
            "(or let every peer in with --allow-any-peer), or bind 127.0.0.1");
}

TEST(PeerPolicyRule, BeyondLoopbackTakesAnAllowListOrAllowAnyPeer) {
  auto listed = makePeerPolicy(Endpoint{0, 502}, modbusOptions("192.168.1.0/24,10.0.0.7"));
  ASSERT_TRUE(listed) << listed.error();
  EXPECT_TRUE(listed->allows(0xc0a80117));   // 192.168.1.23
  EXPECT_TRUE(listed->allows(0x0a000007));   // 10.0.0.7
  EXPECT_FALSE(listed->allows(0x0a000008));  // 10.0.0.8
  EXPECT_FALSE(listed->allows(0xc0a80201));  // 192.168.2.1
  auto any = makePeerPolicy(Endpoint{0, 502}, modbusOptions("", true));
  ASSERT_TRUE(any) << any.error();
  EXPECT_TRUE(any->allows(0x08080808));
}

TEST(PeerPolicyRule, BadAllowListsNameTheOptionAndTheItem) {
  EXPECT_EQ(makePeerPolicy(Endpoint{}, modbusOptions("10.0.0.1,nope")).error(),
            "--modbus-allow: 'nope' is not an IPv4 address (expected ADDRESS or ADDRESS/BITS)");
  EXPECT_EQ(makePeerPolicy(Endpoint{}, modbusOptions("10.0.0.0/33")).error(),
            "--modbus-allow: '33' is not a prefix length (0-32) in 10.0.0.0/33");
  EXPECT_EQ(makePeerPolicy(Endpoint{}, modbusOptions("10.0.0.1/8")).error(),
            "--modbus-allow: '10.0.0.1/8' has host bits set: the network is 10.0.0.0/8");
  EXPECT_EQ(makePeerPolicy(Endpoint{}, modbusOptions(",")).error(), "--modbus-allow: the allow-list names no address");
}

TEST(PeerPolicyAdmit, RefusesBeyondTheLimitsAndLogsPeerAndReason) {
  PeerPolicy policy({Ipv4Net{0x0a000000, 0xff000000}}, PeerLimits{.maxConnections = 3, .maxPerPeer = 2}, "ads", "--ads-allow");
  std::vector<std::string> log;
  policy.setLog([&](const std::string& line) { log.push_back(line); });
  EXPECT_EQ(policy.admit(0x0a000001, 0, 0), Refusal::None);
  EXPECT_EQ(policy.admit(0x0a000001, 2, 1), Refusal::None);
  EXPECT_EQ(policy.admit(0x0a000001, 2, 2), Refusal::PeerFull);
  EXPECT_EQ(policy.admit(0x0a000002, 3, 0), Refusal::ServerFull);
  EXPECT_EQ(policy.admit(0x0b000001, 0, 0), Refusal::NotAllowed);
  EXPECT_EQ(log, (std::vector<std::string>{
                     "ads: refused 10.0.0.1: this address has its 2 connections (--max-clients-per-peer)",
                     "ads: refused 10.0.0.2: the server has its 3 connections (--max-clients)",
                     "ads: refused 11.0.0.1: not in --ads-allow",
                 }));
}

TEST(PeerPolicyAdmit, DefaultsLetAHundredClientProcessesOfOneMachineIn) {
  PeerPolicy policy;
  for (size_t open = 0; open < 100; ++open) EXPECT_EQ(policy.admit(0x7f000001, open, open), Refusal::None) << open;
}

TEST(RequestBudget, ABurstOfOneSecondThenTheRate) {
  RequestBudget budget(4);  // 4 a second: one every 250 ms
  const int64_t t0 = 5'000'000'000;
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(budget.take(t0)) << i;
  EXPECT_FALSE(budget.take(t0));
  EXPECT_FALSE(budget.take(t0 + 200'000'000));
  EXPECT_TRUE(budget.take(t0 + 260'000'000));
  EXPECT_FALSE(budget.take(t0 + 270'000'000));
  // A long pause refills one second's worth, no more.
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(budget.take(t0 + 60'000'000'000)) << i;
  EXPECT_FALSE(budget.take(t0 + 60'000'000'000));
}

TEST(RequestBudget, ZeroIsNoLimit) {
  RequestBudget budget(0);
  for (int i = 0; i < 10000; ++i) ASSERT_TRUE(budget.take(0));
}

}  // namespace
}  // namespace virtcom::proto::net
