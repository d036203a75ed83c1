// The server builds on common/ and proto/'s formats only (DESIGN.md): nothing of the clients'
// HTTP code (what both ends need of HTTP is proto/api/http_headers.h), no OpenCV, no client,
// vision or synthetic-scene code. OpenCV stays out of its compiler flags (reenact_proto links
// it privately) and out of its binary's needed libraries.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/include_scan.h"

namespace reenact::test_support {
namespace {

using testing::IsEmpty;

TEST(ServerDependencies, IncludesNoClientHttpCodeAndNoOpenCv) {
  EXPECT_THAT(BreakingUnder("server",
                            [](const IncludeLine& i) {
                              return i.header == "proto/api/http_client.h" ||
                                     i.header == "proto/api/api_client.h" ||
                                     IsOpenCvHeader(i.header);
                            }),
              IsEmpty());
}

TEST(ServerDependencies, IncludesNoClientVisionOrSyntheticCode) {
  EXPECT_THAT(BreakingUnder("server",
                            [](const IncludeLine& i) {
                              return StartsWithAnyOf(i.header, {"capture-client/", "viewer-client/",
                                                                "vision/", "synthetic/"});
                            }),
              IsEmpty());
}

// compile_commands.json (CMAKE_EXPORT_COMPILE_COMMANDS) holds every source's compiler command:
// no OpenCV include directory reaches a server source.
TEST(ServerDependencies, CompilesWithoutOpenCvIncludeDirectories) {
  std::ifstream in(std::filesystem::path(REENACT_BINARY_DIR) / "compile_commands.json");
  ASSERT_TRUE(in) << "no compile_commands.json in " << REENACT_BINARY_DIR;
  const std::string server_dir = std::string(REENACT_SOURCE_DIR) + "/server/";
  int sources = 0;
  for (const nlohmann::json& entry : nlohmann::json::parse(in)) {
    const std::string file = entry.at("file").get<std::string>();
    if (!StartsWith(file, server_dir)) continue;
    ++sources;
    const std::string command = entry.at("command").get<std::string>();
    EXPECT_EQ(command.find("opencv"), std::string::npos) << file << ": " << command;
  }
  EXPECT_GT(sources, 10);
}

// The dynamic section of reenact-server names the shared libraries it needs; OpenCV is not one
// (the static reenact_proto puts it on the link line, but nothing the server uses calls it).
TEST(ServerDependencies, BinaryNeedsNoOpenCvLibrary) {
  const auto binary = std::filesystem::path(REENACT_BINARY_DIR) / "server" / "reenact-server";
  std::ifstream in(binary, std::ios::binary);
  ASSERT_TRUE(in) << binary << " is not built";
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  EXPECT_NE(bytes.find("libsqlite3.so"), std::string::npos) << "no needed libraries in " << binary;
  EXPECT_EQ(bytes.find("libopencv"), std::string::npos) << binary << " needs OpenCV";
}

}  // namespace
}  // namespace reenact::test_support
