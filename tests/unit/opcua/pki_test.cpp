// The PKI folder: the generated application instance certificate (RSA-2048, the application URI
// in subjectAltName, key file 0600), its reuse, the trust list and the rejected folder that is
// the operator's workflow, and the error of a folder that cannot be made.
#include "proto/opcua/pki.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "proto/opcua/security_policy.hpp"

namespace virtcom::proto::opcua {
namespace {

namespace fs = std::filesystem;

class PkiTest : public ::testing::Test {
 protected:
  void SetUp() override { root_ = fs::temp_directory_path() / ("virtcom-pki-" + std::to_string(::getpid())); }
  void TearDown() override { fs::remove_all(root_); }
  fs::path root_;
};

TEST_F(PkiTest, FirstStartGeneratesTheCertificateAndLaterStartsReuseIt) {
  auto pki = openPki((root_ / "pki").string(), "urn:host:virtcom");
  ASSERT_TRUE(pki) << pki.error();
  for (const char* sub : {"own/certs", "own/private", "trusted/certs", "rejected/certs"}) EXPECT_TRUE(fs::is_directory(root_ / "pki" / sub)) << sub;
  struct stat key {};
  ASSERT_EQ(::stat((root_ / "pki/own/private/virtcom.pem").c_str(), &key), 0);
  EXPECT_EQ(key.st_mode & 0777, 0600u);
  EXPECT_EQ(rsaKeyBytes(pki->certificate), 256u);
  EXPECT_EQ(certificateUri(pki->certificate), "urn:host:virtcom");
  EXPECT_NE(pki->keyPem.find("BEGIN PRIVATE KEY"), std::string::npos);
  auto again = openPki((root_ / "pki").string(), "urn:host:virtcom");
  ASSERT_TRUE(again) << again.error();
  EXPECT_EQ(again->certificate, pki->certificate);
  EXPECT_EQ(again->thumbprint, pki->thumbprint);
}

TEST_F(PkiTest, AnUntrustedClientIsRejectedUntilTheOperatorMovesItsCertificate) {
  auto server = openPki((root_ / "server").string(), "urn:s");
  auto client = openPki((root_ / "client").string(), "urn:c");
  ASSERT_TRUE(server && client);
  const int64_t now = ::time(nullptr);
  PeerCheck first = checkPeerCertificate(*server, client->certificate, now);
  EXPECT_EQ(first.trust, PeerTrust::Untrusted);
  std::vector<fs::path> rejected;
  for (const auto& e : fs::directory_iterator(root_ / "server/rejected/certs")) rejected.push_back(e.path());
  ASSERT_EQ(rejected.size(), 1u);
  EXPECT_NE(first.message.find("move " + rejected[0].string()), std::string::npos) << first.message;
  fs::rename(rejected[0], root_ / "server/trusted/certs" / rejected[0].filename());
  EXPECT_EQ(checkPeerCertificate(*server, client->certificate, now).trust, PeerTrust::Trusted);
  Pki any = *server;
  any.trustAny = true;
  EXPECT_EQ(checkPeerCertificate(any, server->certificate, now).trust, PeerTrust::Trusted);
}

TEST_F(PkiTest, ExpiredAndUnreadableCertificatesAreInvalid) {
  auto server = openPki((root_ / "server").string(), "urn:s");
  ASSERT_TRUE(server);
  Pki any = *server;
  any.trustAny = true;
  const int64_t inTwentyYears = ::time(nullptr) + 20LL * 365 * 86400;
  PeerCheck expired = checkPeerCertificate(any, server->certificate, inTwentyYears);
  EXPECT_EQ(expired.trust, PeerTrust::Invalid);
  EXPECT_NE(expired.message.find("validity"), std::string::npos);
  const std::vector<uint8_t> junk{1, 2, 3};
  EXPECT_EQ(checkPeerCertificate(any, junk, ::time(nullptr)).trust, PeerTrust::Invalid);
}

TEST_F(PkiTest, AFolderThatCannotBeMadeIsNamedInTheError) {
  fs::create_directories(root_);
  std::ofstream(root_ / "file") << "x";
  auto pki = openPki((root_ / "file/pki").string(), "urn:s");
  ASSERT_FALSE(pki);
  EXPECT_NE(pki.error().find((root_ / "file/pki").string()), std::string::npos) << pki.error();
  EXPECT_NE(pki.error().find("cannot create"), std::string::npos) << pki.error();
}

}  // namespace
}  // namespace virtcom::proto::opcua
