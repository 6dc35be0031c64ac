#include "proto/net/link_loss.hpp"

namespace virtcom::proto::net {

void LinkLoss::lost(const std::string& what) { lostAs(policy_.protocol + ": link to " + policy_.peer + " lost: " + what); }

void LinkLoss::lostAs(std::string text) {
  if (policy_.faultOnLoss) return failWith(std::move(text));
  if (!reportedLoss_ && policy_.report) policy_.report(text + " (holding the last commands, retrying " + policy_.retrying + ")");
  reportedLoss_ = true;
}

void LinkLoss::refused(const std::string& what) { failWith(policy_.protocol + ": " + policy_.peer + " " + what); }

void LinkLoss::reconnected() {
  if (reportedLoss_ && policy_.report) policy_.report(policy_.protocol + ": reconnected to " + policy_.peer);
  reportedLoss_ = false;
}

bool LinkLoss::recheckPassed(const std::vector<SignalProblem>& problems, const std::function<void()>& close) {
  if (problems.empty()) return true;
  const SignalProblem& first = problems.front();
  if (first.signal == kNoSignal) {
    close();
    lostAs(first.text);  // a whole sentence already ("ads: link to ... lost: ...")
  } else {
    refused("no longer matches the cell after reconnecting: " + first.text);
  }
  return false;
}

void LinkLoss::failWith(std::string text) {
  if (failure_.empty()) failure_ = std::move(text);
}

}  // namespace virtcom::proto::net
