#pragma once
// The server as every connection sees it (the OPC UA counterpart of ads::Device): the address
// space, the last published memory image, the writes waiting for the next scan, the sessions.
// Not thread-safe: the server holds one mutex around every call (see server.hpp).
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/endpoint.hpp"
#include "proto/ads/write_queue.hpp"
#include "proto/net/peer_policy.hpp"
#include "proto/opcua/address_space.hpp"
#include "proto/opcua/pki.hpp"
#include "proto/opcua/security_policy.hpp"
#include "proto/opcua/subscription.hpp"
#include "proto/opcua/types.hpp"
#include "proto/opcua/user_accounts.hpp"

namespace virtcom::proto::opcua {

inline constexpr uint16_t kDefaultPort = 4840;

struct ServerConfig {
  Endpoint listen{0x7f000001, kDefaultPort};
  net::PeerPolicy peers;                   // who may connect, how many at once, how fast (docs/security.md)
  size_t maxSessions = 32;                 // beyond: BadTooManySessions
  uint32_t maxMessageBytes = 4 * 1024 * 1024;  // a request or response; beyond: BadRequestTooLarge / ERR
  uint32_t receiveBufferBytes = 65536;     // the largest chunk the server takes
  size_t maxOperations = 10000;            // nodes of one Read, Write, Browse...; beyond: BadTooManyOperations
  size_t maxContinuationPoints = 16;       // Browse continuation points per session
  size_t maxSubscriptions = 16;            // per session; beyond: BadTooManySubscriptions
  size_t maxMonitoredItems = 10000;        // per subscription; beyond: BadTooManyMonitoredItems
  size_t maxPublishRequests = 10;          // queued per session; beyond: BadTooManyPublishRequests
  bool readOnly = false;                   // every Write refused (BadUserAccessDenied), whoever the user
  std::vector<UserAccount> users;          // --opcua-users: who may log on with a password; empty: nobody
  UserAccess anonymous = UserAccess::Read;  // what an anonymous session may do; None: anonymous refused. Not
                                           // Write by default: writing is for who was let in (issue 20)
  size_t writeQueueBytes = 64 * 1024;      // written data between two scans
  AddressSpaceConfig names;
  std::string endpointUrl;                 // what GetEndpoints announces; empty: opc.tcp://listen
  // --opcua-security: the endpoints, one per mode (None with policy None, the others with
  // Basic256Sha256); `pki` (--opcua-pki) is set when one is not None.
  std::vector<SecurityMode> securityModes{SecurityMode::None};
  std::shared_ptr<const Pki> pki;
};

// A Browse that stopped at RequestedMaxReferencesPerNode, to be resumed by BrowseNext.
struct ContinuationPoint {
  uint32_t id = 0;
  uint32_t node = 0, nextReference = 0, maxReferences = 0;
  uint32_t direction = 0, referenceType = 0, nodeClassMask = 0, resultMask = 0;
  bool includeSubtypes = true;
};

struct Session {
  uint32_t id = 0;             // ns=1;i=id is the SessionId
  uint32_t token = 0;          // ns=1;i=token is the AuthenticationToken
  uint32_t channelId = 0;      // the channel it was last used on
  bool activated = false;
  UserAccess access = UserAccess::None;  // of the identity it was activated with
  SecurityMode securityMode = SecurityMode::None;  // of the channel it was created on: never activated on a lower one
  std::vector<uint8_t> clientCertificate;          // of that channel (DER; empty with mode None)
  std::array<uint8_t, kSecureNonceBytes> nonce{};  // the last server nonce sent, which the client signs
  double timeoutMs = 0;
  int64_t lastUsedNs = 0;
  std::string name;
  std::vector<ContinuationPoint> continuationPoints;
  uint32_t nextContinuationPoint = 1;
  std::vector<Subscription> subscriptions;
  std::deque<PendingPublish> publishes;
};

class ServerCore {
 public:
  ServerCore(const ads::SymbolTable& table, ServerConfig config);

  const ServerConfig& config() const { return config_; }
  const AddressSpace& space() const { return space_; }
  std::string endpointUrl() const;
  // The endpoint really bound (its port when 0 was asked for): what endpointUrl() names.
  void setBound(const Endpoint& bound) { config_.listen = bound; }

  // The published image (zero until the first publish) and the writes waiting for the scan.
  std::span<const uint8_t> snapshot() const { return snapshot_; }
  // Checks a write of `bytes` into the variable whole, queues it and applies it to the snapshot
  // (so it reads back at once). 0 or a Bad status (BadTooManyOperations when the queue is full);
  // the caller has checked the session may write.
  uint32_t write(const PlcValue& v, std::span<const uint8_t> bytes);
  ads::WriteQueue& pendingWrites() { return pending_; }
  void publish(std::span<const uint8_t> image, std::span<const uint8_t> extra = {});

  // Sessions: nullptr when there are maxSessions already (after dropping timed-out ones).
  Session* createSession(uint32_t channelId, double timeoutMs, std::string name, int64_t nowNs);
  // The session of an AuthenticationToken, or nullptr.
  Session* findSession(const NodeId& token);
  void closeSession(uint32_t id);
  size_t sessionCount() const { return sessions_.size(); }
  std::vector<Session>& sessions() { return sessions_; }
  uint32_t newSubscriptionId() { return nextSubscriptionId_++; }

  // Whether GetEndpoints announces an endpoint of `mode`.
  bool offers(SecurityMode mode) const;
  uint32_t newChannelId() { return nextChannelId_++; }
  uint32_t newTokenId() { return nextTokenId_++; }
  DateTime startTime() const { return startTime_; }

 private:
  ServerConfig config_;
  AddressSpace space_;
  std::vector<uint8_t> snapshot_;
  ads::WriteQueue pending_;
  std::vector<Session> sessions_;
  uint32_t nextSubscriptionId_ = 1;
  uint32_t nextSessionId_ = 1, nextChannelId_ = 1, nextTokenId_ = 1;
  uint32_t tokenSalt_ = 0;
  DateTime startTime_;
};

// The current UTC time as an OPC UA DateTime.
DateTime dateTimeNow();

}  // namespace virtcom::proto::opcua
