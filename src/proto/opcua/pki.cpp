#include "proto/opcua/pki.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "proto/opcua/crypto.hpp"
#include "proto/opcua/security_policy.hpp"

namespace virtcom::proto::opcua {

namespace {

namespace fs = std::filesystem;

constexpr const char* kCertificateFile = "own/certs/virtcom.der";
constexpr const char* kKeyFile = "own/private/virtcom.pem";
constexpr uint32_t kCertificateDays = 3650;
constexpr size_t kMinRsaBytes = 256, kMaxRsaBytes = 512;  // the policy's 2048 to 4096 bits

std::expected<std::string, std::string> readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::unexpected(path.string() + ": cannot read: " + std::strerror(errno));
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Writes `bytes` to a new file of mode `mode` (the key: 0600 from its creation on, never wider).
std::expected<void, std::string> writeNewFile(const fs::path& path, std::span<const uint8_t> bytes, mode_t mode) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, mode);
  if (fd < 0) return std::unexpected(path.string() + ": cannot write: " + std::strerror(errno));
  const bool written = ::write(fd, bytes.data(), bytes.size()) == static_cast<ssize_t>(bytes.size());
  const int error = errno;
  const bool closed = ::close(fd) == 0;
  if (!written || !closed) return std::unexpected(path.string() + ": cannot write: " + std::strerror(written ? errno : error));
  return {};
}

std::expected<void, std::string> makeLayout(const fs::path& dir) {
  for (const char* sub : {"own/certs", "own/private", "trusted/certs", "rejected/certs"}) {
    std::error_code ec;
    fs::create_directories(dir / sub, ec);
    if (ec) return std::unexpected((dir / sub).string() + ": cannot create the folder: " + ec.message());
  }
  ::chmod((dir / "own/private").c_str(), 0700);
  if (::access(dir.c_str(), W_OK) != 0) return std::unexpected(dir.string() + ": the PKI folder is not writable");
  return {};
}

std::string hostName() {
  char name[256] = {};
  return ::gethostname(name, sizeof name - 1) == 0 && name[0] ? name : "localhost";
}

std::expected<void, std::string> generate(const fs::path& dir, const std::string& applicationUri) {
  const CryptoCalls& c = crypto();
  std::vector<uint8_t> cert(8192);
  std::string key(8192, '\0');
  size_t certLength = 0, keyLength = 0;
  if (!c.makeCertificate("virtcom", applicationUri.c_str(), hostName().c_str(), kCertificateDays, cert.data(), cert.size(), &certLength,
                         key.data(), key.size(), &keyLength))
    return std::unexpected(dir.string() + ": could not generate the application instance certificate (OpenSSL)");
  cert.resize(certLength);
  auto keyBytes = std::span(reinterpret_cast<const uint8_t*>(key.data()), keyLength);
  if (auto k = writeNewFile(dir / kKeyFile, keyBytes, 0600); !k) return k;
  return writeNewFile(dir / kCertificateFile, cert, 0644);
}

bool fileEquals(const fs::path& path, std::span<const uint8_t> bytes) {
  auto text = readFile(path);
  return text && text->size() == bytes.size() && std::equal(bytes.begin(), bytes.end(), text->begin(),
                                                           [](uint8_t a, char b) { return a == static_cast<uint8_t>(b); });
}

bool inTrustList(const fs::path& dir, std::span<const uint8_t> certificate) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir / "trusted/certs", ec))
    if (entry.is_regular_file() && fileEquals(entry.path(), certificate)) return true;
  return false;
}

// $XDG_DATA_HOME, else ~/.local/share.
std::string dataDir() {
  const char* data = std::getenv("XDG_DATA_HOME");
  if (data && *data) return data;
  const char* home = std::getenv("HOME");
  return std::string(home && *home ? home : ".") + "/.local/share";
}

}  // namespace

std::string defaultPkiDir() { return dataDir() + "/virtcom/opcua-pki"; }

std::string defaultClientPkiDir() { return dataDir() + "/virtcom/opcua-client-pki"; }

std::expected<Pki, std::string> openPki(const std::string& dir, const std::string& applicationUri) {
  const fs::path root(dir);
  if (auto made = makeLayout(root); !made) return std::unexpected(made.error());
  if (!fs::exists(root / kCertificateFile) || !fs::exists(root / kKeyFile))
    if (auto made = generate(root, applicationUri); !made) return std::unexpected(made.error());
  auto cert = readFile(root / kCertificateFile);
  if (!cert) return std::unexpected(cert.error());
  auto key = readFile(root / kKeyFile);
  if (!key) return std::unexpected(key.error());
  Pki pki;
  pki.dir = dir;
  pki.certificate.assign(cert->begin(), cert->end());
  pki.keyPem = std::move(*key);
  if (rsaKeyBytes(pki.certificate) < kMinRsaBytes)
    return std::unexpected((root / kCertificateFile).string() + ": not an RSA certificate of 2048 bits or more");
  if (!crypto().sha1(pki.certificate.data(), pki.certificate.size(), pki.thumbprint.data()))
    return std::unexpected((root / kCertificateFile).string() + ": cannot hash the certificate");
  return pki;
}

std::string certificateUri(std::span<const uint8_t> certificate) {
  int64_t notBefore = 0, notAfter = 0;
  std::string uri(kMaxCertificateUri, '\0');
  size_t length = 0;
  uint32_t bits = 0;
  if (!crypto().certificateFacts(certificate.data(), certificate.size(), &notBefore, &notAfter, uri.data(), uri.size(), &length, &bits))
    return {};
  uri.resize(length);
  return uri;
}

PeerCheck checkPeerCertificate(const Pki& pki, std::span<const uint8_t> certificate, int64_t nowUnixSeconds, const std::string& peer) {
  int64_t notBefore = 0, notAfter = 0;
  char uri[kMaxCertificateUri];
  size_t uriLength = 0;
  uint32_t bits = 0;
  if (!crypto().certificateFacts(certificate.data(), certificate.size(), &notBefore, &notAfter, uri, sizeof uri, &uriLength, &bits))
    return {PeerTrust::Invalid, "the " + peer + " certificate is not a readable X.509 certificate"};
  if (bits / 8 < kMinRsaBytes || bits / 8 > kMaxRsaBytes)
    return {PeerTrust::Invalid, "the " + peer + " certificate's key is not RSA of 2048 to 4096 bits (Basic256Sha256)"};
  if (nowUnixSeconds < notBefore || nowUnixSeconds > notAfter)
    return {PeerTrust::Invalid, "the " + peer + " certificate is not valid now (outside its validity period)"};
  if (pki.trustAny || inTrustList(pki.dir, certificate)) return {PeerTrust::Trusted, {}};
  uint8_t thumbprint[20];
  const fs::path rejected = fs::path(pki.dir) / "rejected/certs" /
                            ((crypto().sha1(certificate.data(), certificate.size(), thumbprint) ? lowerHex(thumbprint) : peer) + ".der");
  auto written = writeNewFile(rejected, certificate, 0644);
  return {PeerTrust::Untrusted, "the " + peer + " certificate is not trusted; " +
                                    (written ? "to trust it, move " + rejected.string() + " to " +
                                                   (fs::path(pki.dir) / "trusted/certs").string() + "/"
                                             : written.error())};
}

}  // namespace virtcom::proto::opcua
