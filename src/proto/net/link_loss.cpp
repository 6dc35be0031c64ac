#include "proto/net/link_loss.hpp"

namespace virtcom::proto::net {

void LinkLoss::lost(const std::string& what) {
  std::string text = policy_.protocol + ": link to " + policy_.peer + " lost: " + what;
  if (policy_.faultOnLoss) return failWith(std::move(text));
  if (!reportedLoss_ && policy_.report) policy_.report(text + " (holding the last commands, retrying " + policy_.retrying + ")");
  reportedLoss_ = true;
}

void LinkLoss::refused(const std::string& what) { failWith(policy_.protocol + ": " + policy_.peer + " " + what); }

void LinkLoss::reconnected() {
  if (reportedLoss_ && policy_.report) policy_.report(policy_.protocol + ": reconnected to " + policy_.peer);
  reportedLoss_ = false;
}

void LinkLoss::failWith(std::string text) {
  if (failure_.empty()) failure_ = std::move(text);
}

}  // namespace virtcom::proto::net
