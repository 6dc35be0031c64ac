// cell::parseAdsRoutes / appendAdsRoute, the route table of `--ads-routes FILE`: routes read with
// their positions, every mistake reported at file:line:col, an added route appended and read back.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cell/ads_routes.hpp"

namespace virtcom::cell {
namespace {

struct Parsed {
  std::optional<std::vector<AdsRoute>> routes;
  std::string messages;
};

Parsed parse(const std::string& text) {
  SourceManager sources;
  Diagnostics diags;
  Parsed p;
  p.routes = parseAdsRoutes("routes.yaml", text, sources, diags);
  p.messages = diags.render(sources);
  return p;
}

TEST(AdsRoutes, RoutesAreReadWithNameNetIdAndAddress) {
  auto p = parse("routes:\n  - name: hmi-pc\n    netid: 192.168.1.20.1.1\n    address: 192.168.1.20\n"
                 "  - {name: scada, netid: 10.0.0.7.1.1, address: 10.0.0.7}\n");
  ASSERT_TRUE(p.routes) << p.messages;
  ASSERT_EQ(p.routes->size(), 2u);
  EXPECT_EQ((*p.routes)[0].name, "hmi-pc");
  EXPECT_EQ(formatNetId((*p.routes)[0].netId), "192.168.1.20.1.1");
  EXPECT_EQ((*p.routes)[0].ipv4, 0xc0a80114u);
  EXPECT_EQ((*p.routes)[1].ipv4, 0x0a000007u);
}

TEST(AdsRoutes, AnEmptyFileOrAnEmptyListHasNoRoutes) {
  for (const char* text : {"", "routes:\n", "# none yet\nroutes: []\n"}) {
    auto p = parse(text);
    ASSERT_TRUE(p.routes) << text << p.messages;
    EXPECT_TRUE(p.routes->empty()) << text;
  }
}

TEST(AdsRoutes, MistakesAreReportedAtTheirPositionWithWhatIsExpected) {
  auto p = parse("routes:\n  - name: hmi-pc\n    netid: 192.168.1.20\n    address: 192.168.1.20\n");
  EXPECT_FALSE(p.routes);
  EXPECT_NE(p.messages.find("routes.yaml:3:12: error[C010]: 'netid': '192.168.1.20' is not an AmsNetId"), std::string::npos) << p.messages;

  p = parse("routes:\n  - name: hmi-pc\n    netid: 1.2.3.4.1.1\n    address: pc.local\n");
  EXPECT_FALSE(p.routes);
  EXPECT_NE(p.messages.find("routes.yaml:4:14: error[C010]: 'address': "), std::string::npos) << p.messages;
  EXPECT_NE(p.messages.find("the peer's IPv4 address"), std::string::npos) << p.messages;

  p = parse("routes:\n  - name: hmi-pc\n    netid: 1.2.3.4.1.1\n");
  EXPECT_FALSE(p.routes);
  EXPECT_NE(p.messages.find("routes.yaml:2:5: error[C010]"), std::string::npos) << p.messages;
  EXPECT_NE(p.messages.find("address"), std::string::npos) << p.messages;

  p = parse("route:\n  - name: x\n");
  EXPECT_FALSE(p.routes);
  EXPECT_NE(p.messages.find("routes.yaml:1:1: error[C011]"), std::string::npos) << p.messages;

  p = parse("routes: 5\n");
  EXPECT_FALSE(p.routes);
  EXPECT_NE(p.messages.find("'routes' must be a list"), std::string::npos) << p.messages;
}

TEST(AdsRoutes, AnAppendedRouteIsReadBackAfterTheOnesBefore) {
  const auto path = (std::filesystem::temp_directory_path() / ("virtcom_routes_" + std::to_string(::getpid()) + ".yaml")).string();
  std::filesystem::remove(path);
  ASSERT_EQ(appendAdsRoute(path, {"first", {10, 0, 0, 1, 1, 1}, 0x0a000001}), "");
  ASSERT_EQ(appendAdsRoute(path, {"second", {10, 0, 0, 2, 1, 1}, 0x0a000002}), "");
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::filesystem::remove(path);
  auto p = parse(text.str());
  ASSERT_TRUE(p.routes) << p.messages << text.str();
  ASSERT_EQ(p.routes->size(), 2u);
  EXPECT_EQ((*p.routes)[0].name, "first");
  EXPECT_EQ((*p.routes)[1].name, "second");
  EXPECT_EQ(formatNetId((*p.routes)[1].netId), "10.0.0.2.1.1");
  EXPECT_EQ((*p.routes)[1].ipv4, 0x0a000002u);
  EXPECT_EQ(appendAdsRoute("/nonexistent-dir/routes.yaml", {"x", {}, 0}),
            "cannot write the ADS routes file '/nonexistent-dir/routes.yaml': No such file or directory");
}

// A route added over UDP is appended while the server runs: a kill -9 at any moment of an append
// leaves the file whole (it parses, every route complete) with the routes whose append finished,
// so the next start reads it (core/atomic_file.hpp). A child appends without end; once it has
// added a route it is killed at a different moment of a later append each round (an append
// takes a few ms to tens of ms: it syncs the file to the disk).
TEST(AdsRoutes, AKillMidAppendLeavesTheFileWhole) {
  const auto dir = std::filesystem::temp_directory_path() / ("virtcom_routes_kill_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "routes.yaml").string();
  size_t had = 0;
  auto fileSize = [&] {
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    return ec ? std::uintmax_t{0} : size;
  };
  for (int round = 0; round < 12; ++round) {
    const auto before = fileSize();
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      for (int i = 0;; ++i)
        if (!appendAdsRoute(path, {"r" + std::to_string(round) + "-" + std::to_string(i), {10, 0, 0, 1, 1, 1}, 0x0a000001}).empty())
          ::_exit(1);
    }
    for (int wait = 0; wait < 10'000 && fileSize() == before; ++wait) ::usleep(1000);
    ::usleep(static_cast<useconds_t>(1700 * round));
    ASSERT_EQ(::kill(child, SIGKILL), 0);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the child failed to append: exit " << WEXITSTATUS(status);
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    auto p = parse(text.str());
    ASSERT_TRUE(p.routes) << "round " << round << ": " << p.messages;
    EXPECT_GT(p.routes->size(), had) << "round " << round << ": the route added before the kill is kept";
    had = p.routes->size();
  }
  std::filesystem::remove_all(dir);  // with the temporary files the killed children left
}

}  // namespace
}  // namespace virtcom::cell
