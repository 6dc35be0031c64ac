// Start-up (issue 17): the executable does not load the heavy libraries only some commands use;
// those commands load them from the modules built beside it (core/bundled_module.hpp), serve
// and draw through them, and say clearly which file is missing when one is.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "server_process.hpp"
#include "shell_command.hpp"
#include "support/loopback_client.hpp"

namespace {

using virtcom::e2e::ServerProcess;
using virtcom::e2e::shell;
using virtcom::test::LoopbackClient;

const std::string kExe = VIRTCOM_EXE;
const std::string kGearbox = std::string(VIRTCOM_SOURCE_DIR) + "/examples/gearbox-cell";
const std::string kActivity = std::string(VIRTCOM_SOURCE_DIR) + "/examples/activity";

TEST(StartUp, TheExecutableNeedsNeitherTheHttpNorTheGraphvizNorTheMpiLibraries) {
  std::string out;
  ASSERT_EQ(shell("readelf -d " + kExe, out), 0) << out;
  ASSERT_NE(out.find("(NEEDED)"), std::string::npos) << out;
  // libcrypto is not in the list: the OPC UA server's password hashes (proto/opcua/user_accounts)
  // need it in the executable (docs/performance.md, start-up).
  for (const char* library : {"libcpp-httplib", "libssl", "libbrotli", "libgvc", "libcgraph", "libgvplugin", "libmpi", "libopen-"})
    EXPECT_EQ(out.find(library), std::string::npos) << library << " is loaded by every command:\n" << out;
}

// The executable copied alone into a folder of its own: its modules are not beside it.
class StartUpWithoutModules : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::path(::testing::TempDir()) / ("virtcom_alone_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    exe_ = (dir_ / "virtcom").string();
    std::filesystem::copy_file(kExe, exe_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path dir_;
  std::string exe_;
};

TEST_F(StartUpWithoutModules, ARunNeedsNoModule) {
  std::string out;
  EXPECT_EQ(shell("cd " + kGearbox + " && " + exe_ + " run cell.yaml --set MAIN.sequence=3", out), 0) << out;
  EXPECT_NE(out.find("70.950 s"), std::string::npos) << out;
}

TEST_F(StartUpWithoutModules, DrawingNamesTheMissingGraphvizModule) {
  std::string out;
  EXPECT_EQ(shell("cd " + kActivity + " && " + exe_ + " ad render tank.ad --svg " + (dir_ / "tank.svg").string(), out), 1)
      << out;
  EXPECT_NE(out.find("virtcom ad render: cannot load the module virtcom-graphviz.so (built and installed beside the virtcom "
                     "executable): " + (dir_ / "virtcom-graphviz.so").string() + ": cannot open shared object file"),
            std::string::npos)
      << out;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "tank.svg"));
}

TEST_F(StartUpWithoutModules, ServingTheHmiNamesTheMissingHttpModule) {
  std::string out;
  EXPECT_EQ(shell("cd " + kGearbox + " && " + exe_ + " run cell.yaml --hmi 127.0.0.1:0", out), 64) << out;
  EXPECT_NE(out.find("error: --hmi: cannot load the module virtcom-httplib.so (built and installed beside the virtcom executable): " +
                     (dir_ / "virtcom-httplib.so").string() + ": cannot open shared object file"),
            std::string::npos)
      << out;
}

// Under a launcher (its environment says so) a sweep without the MPI module stops before any
// work: each rank alone would run every point and write the same files.
TEST_F(StartUpWithoutModules, ASweepUnderMpiNamesTheMissingMpiModule) {
  std::string out;
  EXPECT_EQ(shell("cd " + kGearbox + " && OMPI_COMM_WORLD_SIZE=2 " + exe_ + " sweep sweep.yaml", out), 64) << out;
  EXPECT_NE(out.find("error: started by an MPI launcher, but cannot load the module virtcom-mpi.so (built and installed beside the "
                     "virtcom executable): " + (dir_ / "virtcom-mpi.so").string() + ": cannot open shared object file"),
            std::string::npos)
      << out;
  EXPECT_EQ(out.find("points"), std::string::npos) << out;
}

// What the server sends on `client` until `text` arrives (or 5 s pass without data).
std::string receiveUntil(LoopbackClient& client, const std::string& text) {
  std::string got;
  while (got.find(text) == std::string::npos) {
    std::vector<uint8_t> byte = client.receive(1);
    if (byte.empty()) break;
    got.push_back(static_cast<char>(byte[0]));
  }
  return got;
}

TEST(StartUp, TheHmiAnswersAndStreamsThroughItsModule) {
  ServerProcess cell(kExe, {"serve", kGearbox + "/cell.yaml", "--http", "127.0.0.1:0", "--quiet"}, kGearbox,
                     "hmi: serving http://");
  ASSERT_GT(cell.port(), 0) << cell.errorOutput();
  {
    LoopbackClient client(cell.port());
    ASSERT_TRUE(client.connected());
    const std::string request = "GET /api/model HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n";
    ASSERT_TRUE(client.send(std::vector<uint8_t>(request.begin(), request.end())));
    std::string reply = receiveUntil(client, "\"Robot1\"");
    EXPECT_EQ(reply.rfind("HTTP/1.1 200", 0), 0u) << reply;
    EXPECT_NE(reply.find("Cache-Control: no-store"), std::string::npos) << reply;
    EXPECT_NE(reply.find("\"Robot1\""), std::string::npos) << reply;
  }
  {
    LoopbackClient client(cell.port());
    const std::string request = "GET /api/stream HTTP/1.1\r\nHost: x\r\n\r\n";
    ASSERT_TRUE(client.send(std::vector<uint8_t>(request.begin(), request.end())));
    std::string reply = receiveUntil(client, "data: {");
    EXPECT_EQ(reply.rfind("HTTP/1.1 200", 0), 0u) << reply;
    EXPECT_NE(reply.find("Content-Type: text/event-stream"), std::string::npos) << reply;
    EXPECT_NE(reply.find("data: {"), std::string::npos) << reply;
  }
  EXPECT_EQ(cell.stop(), 0) << cell.errorOutput();
}

}  // namespace
