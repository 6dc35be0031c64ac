#pragma once
// The server's PKI folder (`--opcua-pki`, docs/opcua.md "Security"), laid out as node-opcua's and
// UA-.NET's: own/certs (the application instance certificate, DER), own/private (its key, PEM,
// mode 0600), trusted/certs (the client certificates the server accepts, DER) and
// rejected/certs (the ones it refused, for the operator to move to trusted/certs).
#include <array>
#include <cstdint>
#include <expected>
#include <span>
#include <string>
#include <vector>

namespace virtcom::proto::opcua {

struct Pki {
  std::string dir;
  std::vector<uint8_t> certificate;  // DER
  std::string keyPem;
  std::array<uint8_t, 20> thumbprint{};  // SHA-1 of the certificate
  bool trustAny = false;                 // --opcua-trust-any-client: no trust list
};

// $XDG_DATA_HOME/virtcom/opcua-pki, else ~/.local/share/virtcom/opcua-pki.
std::string defaultPkiDir();
// The client bridge's own (`plc: opcua: pki:`), beside the server's: .../virtcom/opcua-client-pki.
std::string defaultClientPkiDir();

// Opens the folder `dir`, creating its layout, and the certificate and key in it; with none
// yet, generates a self-signed RSA-2048 SHA-256 certificate naming `applicationUri` (and this
// host) valid 10 years. The error names the folder or file and what failed.
std::expected<Pki, std::string> openPki(const std::string& dir, const std::string& applicationUri);

enum class PeerTrust : uint8_t { Trusted, Untrusted, Invalid };
struct PeerCheck {
  PeerTrust trust = PeerTrust::Invalid;
  std::string message;  // why not trusted, and what the operator may do about it
};
// Whether a peer's certificate (DER; `peer` names its role in the message: "client", "server") is trusted: an RSA certificate of 2048 to 4096 bits,
// valid at `nowUnixSeconds`, byte for byte one of trusted/certs (or any with trustAny). An
// untrusted one is written to rejected/certs (named by its thumbprint) for the operator.
PeerCheck checkPeerCertificate(const Pki& pki, std::span<const uint8_t> certificate, int64_t nowUnixSeconds,
                               const std::string& peer = "client");

// The first URI of a certificate's subjectAltName (empty if none or unreadable).
std::string certificateUri(std::span<const uint8_t> certificate);

}  // namespace virtcom::proto::opcua
