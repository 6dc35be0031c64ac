#pragma once
// The link-loss policy every protocol client bridge (ADS, OPC UA, Modbus) follows, kept in one place so
// the bridges cannot drift apart in what a lost link does to a run:
//  - a lost link (refused, reset, timeout) fails the run with faultOnLoss; otherwise it is
//    reported once, the devices hold the last commands and the bridge retries;
//  - a refusal by the PLC itself (the program changed) always fails the run;
//  - the first failure wins: later ones are consequences of it.

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace virtcom::proto::net {

inline constexpr size_t kNoSignal = static_cast<size_t>(-1);

// What a bridge found wrong checking the PLC against the cell's wiring.
struct SignalProblem {
  enum class Kind { Link, Unknown, Mismatch };  // connection / the PLC lacks it / not as wired
  size_t signal = kNoSignal;  // index into the bridge's signals; kNoSignal: the connection
  std::string text;
  Kind kind = Kind::Mismatch;
};

struct BridgeStartReport {
  std::vector<SignalProblem> problems;  // every failure, at most one per signal
  std::vector<bool> found;              // per signal: the PLC has it (empty or false: not asked)
};

struct LinkLossPolicy {
  std::string protocol;  // the message prefix, e.g. "ads"
  std::string peer;      // e.g. "the OPC UA server at opc.tcp://127.0.0.1:4840"
  std::string retrying;  // when it retries, e.g. "every poll"
  bool faultOnLoss = true;
  std::function<void(const std::string&)> report;  // connection events, one line each
};

class LinkLoss {
 public:
  explicit LinkLoss(LinkLossPolicy policy) : policy_(std::move(policy)) {}

  // The link broke while doing `what`; the caller has closed its connection.
  void lost(const std::string& what);
  // The PLC answered but refused: `what` follows the peer's name.
  void refused(const std::string& what);
  // The link is back (reported only if its loss was).
  void reconnected();
  // After reconnecting, the bridge checked the cell's signals on the new connection and found
  // `problems`. None: true. The connection's own problem is a loss (`close` closes the
  // connection first; its text is the whole message, as the bridge's start reports it); a
  // signal's is a refusal, the PLC no longer matching the cell.
  bool recheckPassed(const std::vector<SignalProblem>& problems, const std::function<void()>& close);

  bool failed() const { return !failure_.empty(); }
  const std::string& failure() const { return failure_; }

 private:
  void lostAs(std::string text);  // lost(), the whole message given
  void failWith(std::string text);

  LinkLossPolicy policy_;
  bool reportedLoss_ = false;
  std::string failure_;
};

}  // namespace virtcom::proto::net
