#pragma once
// One TCP connection: the Hello/Acknowledge handshake, the secure channel (security policy None
// or Basic256Sha256 with mode Sign or SignAndEncrypt: OpenSecureChannel issue and renew,
// CloseSecureChannel), the chunks of MSG messages and the dispatch of each request to
// services.def (docs/opcua.md, Wire reference: Messages). Pure but for the PKI folder's trust
// list: the server feeds it whole messages and sends what it appends.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "proto/opcua/security_policy.hpp"

#include "proto/opcua/server_core.hpp"
#include "proto/opcua/services.hpp"

namespace virtcom::proto::opcua {

class Channel {
 public:
  explicit Channel(ServerCore& core) : core_(core) {}

  // Answers one whole message (as scanFrame cut it), appending to `tx`. False: close the
  // connection once `tx` is sent (CLO, or an error already answered with ERR).
  bool handleFrame(std::span<const uint8_t> frame, std::vector<uint8_t>& tx, int64_t nowNs);
  uint32_t channelId() const { return channelId_; }
  // Samples the monitored items and answers the Publish requests of this channel's sessions
  // that are due at `nowNs`, appending to `tx`.
  void tick(int64_t nowNs, std::vector<uint8_t>& tx);
  // When tick() has something to do next (INT64_MAX: nothing).
  int64_t nextDueNs();
  // Why the last OpenSecureChannel was refused, for the operator's log (empty: not refused for
  // its certificate); what it says to do (trust the certificate).
  const std::string& rejection() const { return rejection_; }

 private:
  bool onHello(std::span<const uint8_t> body, std::vector<uint8_t>& tx);
  bool onOpen(std::span<const uint8_t> frame, std::vector<uint8_t>& tx);
  // Checks the client's certificate and opens the secured OPN request into `plain` (sequence
  // header and body); false once answered with ERR.
  bool openSecured(std::span<const uint8_t> frame, size_t headerEnd, const ByteString& certificate, const ByteString& thumbprint,
                   std::span<const uint8_t>& plain, std::vector<uint8_t>& tx);
  // The secured channel's new nonces and keys (issue and renew).
  bool renewKeys(const ByteString& clientNonce, std::array<uint8_t, kSecureNonceBytes>& serverNonce);
  // The sequence number of a secured channel's next chunk must follow the last (OPC 10000-6 §6.7.2.4).
  bool sequenceFollows(uint32_t sequence);
  bool onMessage(char chunk, std::span<const uint8_t> frame, std::vector<uint8_t>& tx, int64_t nowNs);
  enum class Reply : uint8_t { Send, Later, Close };
  // Runs the request in `request` (type id, RequestHeader, body) into body_: Send it, nothing
  // yet (a Publish waiting), or close (CloseSecureChannel).
  Reply serve(std::span<const uint8_t> request, uint32_t requestId, int64_t nowNs);
  // Sends body_ as MSG chunks of at most the peer's receive buffer.
  void sendChunks(const char* type, uint32_t requestId, std::vector<uint8_t>& tx);
  bool fail(std::vector<uint8_t>& tx, StatusCodeValue status, const char* reason);

  ServerCore& core_;
  bool hello_ = false;
  uint32_t channelId_ = 0, tokenId_ = 0, previousTokenId_ = 0, sequence_ = 0;
  uint32_t peerReceiveBuffer_ = 0, peerMaxMessage_ = 0;
  std::vector<uint8_t> partial_;  // the chunks so far of a request sent in several
  std::vector<uint8_t> body_;     // the response being built (reused)
  // Security of the channel (mode None: none of it used).
  SecurityMode mode_ = SecurityMode::None;
  AsymmetricKeys asymmetric_;                    // own certificate and key, the client's certificate
  SymmetricKeys clientKeys_, previousClientKeys_;  // what the client signs and encrypts with (current and previous token)
  SymmetricKeys serverKeys_;                     // what the server sends with
  uint32_t lastSequence_ = 0;                    // the client's last sequence number
  std::vector<uint8_t> rx_, scratch_;            // a secured chunk opened in place; an OPN's plaintext (reused)
  std::string rejection_;
};

}  // namespace virtcom::proto::opcua
