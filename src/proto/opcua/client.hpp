#pragma once
// A small blocking OPC UA client (docs/opcua.md, The client bridge): one opc.tcp connection,
// security policy None or Basic256Sha256 (Sign or SignAndEncrypt, with the certificate of its own
// PKI folder; the server's found with GetEndpoints and trusted as the server trusts its clients'),
// one session (anonymous, or a user name and password, encrypted for the server where its token
// policy asks for it), one request at a time, each answered within the timeout or the link counts as lost. Requests and responses are
// built and read with the server's codec (binary_codec.hpp, transport.hpp, services.hpp); the
// caller writes a service's request body and reads its response body. The channel's token is
// renewed before three quarters of its lifetime have passed. Used on the simulation thread by
// the client bridge (client_bridge.hpp).
// Allocation: only when a request or response is larger than any before, when the channel's
// token is renewed (about every 45 minutes) and when a failure's text is made; a secured channel
// signs and encrypts in place.
#include <array>
#include <cstdint>
#include <expected>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "proto/net/endpoint.hpp"
#include "proto/opcua/binary_codec.hpp"
#include "proto/opcua/pki.hpp"
#include "proto/opcua/security_policy.hpp"

namespace virtcom::proto::opcua {

struct ClientConfig {
  net::Endpoint server{0x7f000001, 4840};
  std::string endpointUrl = "opc.tcp://127.0.0.1:4840";  // sent in Hello and CreateSession
  std::string user, password;                            // empty user: an anonymous session
  int64_t timeoutNs = 500'000'000;                       // connect and each request
  double sessionTimeoutMs = 60'000;
  uint32_t bufferBytes = 65536;                          // our receive and send buffers (Hello)
  size_t maxResponseBytes = 16 * 1024 * 1024;            // a longer response is a broken link
  // Basic256Sha256 unless None. Secured, the PKI folder `pkiDir` (its layout as the server's,
  // pki.hpp; a certificate made at the first connect) holds the client's certificate, and the
  // server's must be in its trusted/certs unless `trustAnyServer`.
  SecurityMode security = SecurityMode::None;
  std::string pkiDir;
  bool trustAnyServer = false;
};

struct ClientError {
  bool linkLost = true;  // the connection failed and is closed (refused, reset, timeout, ERR, garbage)
  uint32_t status = 0;   // else: the Bad status of the service (a ServiceFault or its ServiceResult)
  std::string text;      // one line, e.g. "BadNodeIdUnknown" or "connection refused"
};

class Client {
 public:
  explicit Client(ClientConfig config);
  ~Client();  // close()
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  // Connects, opens the secure channel and creates and activates the session. Blocks.
  std::expected<void, ClientError> connect();
  // Closes the session and the channel (best effort, not waiting long), then the socket.
  void close();
  bool connected() const { return fd_ >= 0; }
  const ClientConfig& config() const { return config_; }

  // A request of the service whose request encoding id is `requestTypeId` (OPC 10000-6 Annex A,
  // services.def): its RequestHeader is written; append the body to the Writer returned.
  Writer& beginRequest(uint32_t requestTypeId);
  // Sends it and waits for its response; a Reader at the body after the ResponseHeader, valid
  // until the next request. A ServiceFault or a Bad ServiceResult is an error with linkLost false.
  std::expected<Reader, ClientError> call(uint32_t responseTypeId);
  // Sends the request begun without waiting for its response, which collect() takes (also when it
  // came while call() waited for another): a Publish, answered when the server has something
  // to say. One such request at a time.
  std::expected<void, ClientError> post();
  bool posted() const { return postedId_ != 0; }
  // The posted request's response if it has come, without waiting: a Reader at its body (valid
  // until the next request), or nullopt. Its errors are those of call(); either way the request
  // is no longer posted.
  std::expected<std::optional<Reader>, ClientError> collect(uint32_t responseTypeId);

  // Requests sent so far (session and channel requests included).
  uint64_t requests() const { return requests_; }

 private:
  // Connects the socket and says Hello.
  std::expected<void, ClientError> openTransport();
  std::expected<void, ClientError> handshake();
  // The client's PKI folder, opened once (and the crypto module loaded).
  std::expected<void, ClientError> openOwnPki();
  // GetEndpoints over a connection of its own with security None: the server's certificate from
  // the endpoint of config_.security, if it is trusted.
  std::expected<void, ClientError> discoverServer();
  // OpenSecureChannel (issue or renew) with the security of mode_.
  std::expected<void, ClientError> openChannel(uint32_t requestType);
  // The channel's keys from its two nonces (OPC 10000-6 §6.7.5); false if the server's is not 32 bytes.
  bool deriveChannelKeys(const ByteString& serverNonce);
  std::expected<void, ClientError> createSession();
  std::expected<void, ClientError> activateSession();
  // Sends tx_ (a whole message) and receives the whole response to `requestId` into body_ (the
  // chunks of a MSG joined; of OPN its body after the asymmetric header).
  std::expected<void, ClientError> transact(uint32_t requestId, int64_t deadlineNs);
  std::expected<void, ClientError> receiveMessage(int64_t deadlineNs, std::span<const uint8_t>& frame);
  // Sends body_ (a request) as MSG chunks; its request id.
  std::expected<uint32_t, ClientError> sendRequest(int64_t deadlineNs);
  // Appends the body of one received OPN or MSG chunk to body_ if it answers `requestId`, or to
  // parked_ if it answers the posted request (else drops it: a late answer). True when `requestId`'s
  // final chunk has come.
  std::expected<bool, ClientError> takeChunk(std::span<const uint8_t> frame, uint32_t requestId);
  // The UserNameIdentityToken of config_.user, its password encrypted where the policy asks.
  std::expected<ExtensionObject, ClientError> userNameToken();
  // The NodeId and ResponseHeader of a response body: a Reader at its fields, or the error.
  std::expected<Reader, ClientError> openResponse(std::span<const uint8_t> body, uint32_t responseTypeId);
  // A complete message is buffered or the socket has something (data, its end, an error).
  bool messageWaiting() const;
  void beginMessage(const char* type);
  ClientError lost(std::string what);

  ClientConfig config_;
  int fd_ = -1;
  uint32_t channelId_ = 0, tokenId_ = 0, sequence_ = 0, requestId_ = 0, requestHandle_ = 0;
  int64_t renewAtNs_ = 0;
  uint32_t peerReceiveBuffer_ = 0;
  NodeId authenticationToken_;
  std::string anonymousPolicy_ = "anonymous", userNamePolicy_ = "username";  // from the server's endpoints
  std::string userNameSecurityPolicy_;  // the UserName token's security policy: Basic256Sha256 encrypts the password
  SecurityMode mode_ = SecurityMode::None;  // of the channel open now (None while discovering the server)
  std::optional<Pki> pki_;
  AsymmetricKeys asymmetric_;  // ours, and the server's certificate
  SymmetricKeys clientKeys_, serverKeys_, previousServerKeys_;  // what we send with; what the server sends with (current and previous token)
  uint32_t previousTokenId_ = 0, lastServerSequence_ = 0;
  std::array<uint8_t, kSecureNonceBytes> channelNonce_{};
  std::vector<uint8_t> serverCertificate_, sessionNonce_;  // of CreateSession: what an encrypted password needs
  std::vector<uint8_t> scratch_;  // an OPN response's plaintext
  std::vector<uint8_t> tx_, rx_, body_;  // body_: the request being built, then the response's body
  uint32_t postedId_ = 0;                 // the posted request: its response goes to parked_
  bool parkedDone_ = false;               // parked_ holds the whole response
  std::vector<uint8_t> parked_;
  Writer request_{body_};                 // what beginRequest() hands out: appends to body_
  size_t rxUsed_ = 0, frameSize_ = 0, bodyStart_ = 0;
  uint64_t requests_ = 0;
};

}  // namespace virtcom::proto::opcua
