// The link-loss policy the ADS and OPC UA client bridges share: fault or hold on a lost link,
// a refusal always fails, the first failure wins, loss and recovery are reported once each.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "proto/net/link_loss.hpp"

namespace virtcom::proto::net {
namespace {

struct Reported {
  std::vector<std::string> lines;
  LinkLoss link(bool faultOnLoss) {
    return LinkLoss({"ads", "the PLC at 10.0.0.2:48898", "every step", faultOnLoss,
                     [this](const std::string& line) { lines.push_back(line); }});
  }
};

TEST(LinkLoss, FaultOnLossFailsWithTheFirstLoss) {
  Reported r;
  LinkLoss link = r.link(true);
  link.lost("reading: timeout");
  link.lost("writing: reset");
  EXPECT_TRUE(link.failed());
  EXPECT_EQ(link.failure(), "ads: link to the PLC at 10.0.0.2:48898 lost: reading: timeout");
  EXPECT_TRUE(r.lines.empty());
}

TEST(LinkLoss, HoldingReportsTheLossOnceAndTheRecovery) {
  Reported r;
  LinkLoss link = r.link(false);
  link.lost("reading: timeout");
  link.lost("cannot connect: refused");
  link.reconnected();
  link.reconnected();
  EXPECT_FALSE(link.failed());
  ASSERT_EQ(r.lines.size(), 2u);
  EXPECT_EQ(r.lines[0],
            "ads: link to the PLC at 10.0.0.2:48898 lost: reading: timeout (holding the last commands, retrying every step)");
  EXPECT_EQ(r.lines[1], "ads: reconnected to the PLC at 10.0.0.2:48898");
}

TEST(LinkLoss, ARefusalFailsEvenWhenHolding) {
  Reported r;
  LinkLoss link = r.link(false);
  link.refused("refused writing 'MAIN.x': 0x710");
  link.lost("reading: timeout");
  EXPECT_EQ(link.failure(), "ads: the PLC at 10.0.0.2:48898 refused writing 'MAIN.x': 0x710");
}

// What every bridge does after reconnecting: the cell's signals checked again on the new
// connection; a connection problem is one more loss (the connection closed first), a signal's
// problem means the program changed, which fails the run even when holding. (Regression: the
// connection problem's text, a whole message, was prefixed again: "ads: link to X lost: ads: link
// to X lost: ...".)
TEST(LinkLoss, TheRecheckAfterReconnectingTellsALossFromAChangedProgram) {
  Reported r;
  LinkLoss link = r.link(false);
  int closed = 0;
  auto close = [&] { ++closed; };
  EXPECT_TRUE(link.recheckPassed({}, close));
  EXPECT_FALSE(link.recheckPassed(
      {{kNoSignal, "ads: link to the PLC at 10.0.0.2:48898 lost: reading the symbols: timeout", SignalProblem::Kind::Link}}, close));
  EXPECT_EQ(closed, 1);
  EXPECT_FALSE(link.failed());
  ASSERT_EQ(r.lines.size(), 1u);
  EXPECT_EQ(r.lines[0], "ads: link to the PLC at 10.0.0.2:48898 lost: reading the symbols: timeout (holding the last commands, "
                        "retrying every step)");
  EXPECT_FALSE(link.recheckPassed({{2, "the PLC has no variable 'MAIN.x'", SignalProblem::Kind::Unknown}}, close));
  EXPECT_EQ(closed, 1);
  EXPECT_EQ(link.failure(), "ads: the PLC at 10.0.0.2:48898 no longer matches the cell after reconnecting: the PLC has no variable 'MAIN.x'");
}

}  // namespace
}  // namespace virtcom::proto::net
