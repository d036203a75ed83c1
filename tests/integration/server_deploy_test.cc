// Checks of the shipped deployment files with the tools that read them, where installed:
// systemd-analyze verify for the unit, nginx -t for the proxy configs. A missing tool skips.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/integration/process.h"

namespace reenact {
namespace {

std::string Which(const std::string& tool) {
  for (const char* dir :
       {"/usr/bin", "/usr/sbin", "/bin", "/sbin", "/usr/local/bin", "/usr/local/sbin"}) {
    const std::string path = std::string(dir) + "/" + tool;
    if (access(path.c_str(), X_OK) == 0) return path;
  }
  return "";
}

std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void Replace(std::string& text, const std::string& from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
}

TEST(ServerDeploy, SystemdUnitVerifies) {
  const std::string tool = Which("systemd-analyze");
  if (tool.empty()) GTEST_SKIP() << "systemd-analyze is not installed; unit not verified";
  testing::TempDir tmp;
  // The unit names the installed path; point it at the binary under test.
  std::string unit = ReadFile(std::string(REENACT_SOURCE_DIR) + "/deploy/reenact-server.service");
  ASSERT_FALSE(unit.empty());
  Replace(unit, "/usr/local/bin/reenact-server", testing::kServer);
  const std::string path = tmp.path() + "/reenact-server.service";
  std::ofstream(path) << unit;
  const auto r = testing::RunProcess({tool, "verify", path}, std::chrono::seconds(60));
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(r.err.find("reenact-server.service:"), std::string::npos) << r.err;
}

// nginx -t on deploy/<file>, a conf.d snippet (http context) wrapped in a minimal main config.
void ExpectNginxConfigParses(const std::string& file) {
  const std::string tool = Which("nginx");
  if (tool.empty()) GTEST_SKIP() << "nginx is not installed; proxy config not checked";
  testing::TempDir tmp;
  std::ofstream(tmp.path() + "/nginx.conf")
      << "pid " << tmp.path() << "/nginx.pid;\nerror_log " << tmp.path() << "/error.log;\n"
      << "events {}\nhttp {\n  access_log off;\n  include " << REENACT_SOURCE_DIR
      << "/deploy/" << file << ";\n}\n";
  const auto r = testing::RunProcess(
      {tool, "-t", "-p", tmp.path(), "-c", tmp.path() + "/nginx.conf"}, std::chrono::seconds(60));
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
}

TEST(ServerDeploy, NginxConfigParses) { ExpectNginxConfigParses("nginx-reenact.conf"); }

TEST(ServerDeploy, NginxUpstreamConfigParses) {
  ExpectNginxConfigParses("nginx-reenact-upstream.conf");
}

TEST(ServerDeploy, ContainerfileRunsTheServerAsAnUnprivilegedUser) {
  const std::string text = ReadFile(std::string(REENACT_SOURCE_DIR) + "/deploy/Containerfile");
  ASSERT_FALSE(text.empty());
  EXPECT_NE(text.find("\nUSER reenact"), std::string::npos);
  EXPECT_NE(text.find("reenact-server"), std::string::npos);
}

}  // namespace
}  // namespace reenact
