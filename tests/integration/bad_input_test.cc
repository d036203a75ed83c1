// Bad input at the process level: each a clear one-line error and a non-zero exit, never a hang.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "tests/integration/expect_error.h"
#include "tests/integration/process.h"

namespace reenact {
namespace {

using testing::ExpectOneLineError;
using testing::RunProcess;
using testing::TempDir;

using testing::kBin;
using testing::kCapture;
using testing::kServer;
using testing::kViewer;
constexpr auto kQuick = std::chrono::seconds(30);

class ListeningSocket {
 public:
  ListeningSocket() {
    fd_ = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr);
    listen(fd_, 1);
    socklen_t len = sizeof addr;
    getsockname(fd_, reinterpret_cast<sockaddr*>(&addr), &len);
    port_ = ntohs(addr.sin_port);
  }
  ~ListeningSocket() { close(fd_); }
  int port() const { return port_; }

 private:
  int fd_ = -1;
  int port_ = 0;
};

TEST(BadInput, ServerOnTakenPortFailsClearly) {
  TempDir tmp;
  ListeningSocket taken;
  const auto r = RunProcess({kServer, "serve", "--db", tmp.path() + "/db", "--listen",
                             "127.0.0.1:" + std::to_string(taken.port())},
                            kQuick);
  ExpectOneLineError(r, std::to_string(taken.port()));
}

TEST(BadInput, DemoWithPortTakenFailsClearly) {
  TempDir tmp;
  ListeningSocket taken;
  const auto r = RunProcess({"/bin/bash", std::string(REENACT_SOURCE_DIR) + "/deploy/demo.sh", kBin},
                            std::chrono::seconds(60),
                            {"REENACT_DEMO_PORT=" + std::to_string(taken.port()),
                             "REENACT_DEMO_WORK=" + tmp.path() + "/work",
                             "REENACT_DEMO_OUT=" + tmp.path() + "/out"});
  EXPECT_FALSE(r.timed_out);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("reenact-server did not start"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(std::to_string(taken.port())), std::string::npos) << r.err;
}

TEST(BadInput, UnknownSyntheticScenarioListsKnownOnes) {
  TempDir tmp;
  const auto r = RunProcess({kCapture, "record", "--source", "synthetic:no-such-scene", "--out",
                             tmp.path() + "/clip"}, kQuick);
  ExpectOneLineError(r, "turn-and-kick");
  EXPECT_FALSE(std::filesystem::exists(tmp.path() + "/clip"));
}

TEST(BadInput, OpenNiWithoutDeviceFailsClearly) {
  TempDir tmp;
  const auto r = RunProcess({kCapture, "record", "--source", "openni", "--out",
                             tmp.path() + "/clip"}, kQuick);
  if (r.exit_code == 0) GTEST_SKIP() << "an OpenNI2 device is connected";
  ExpectOneLineError(r, "no OpenNI2 device found");
  EXPECT_FALSE(std::filesystem::exists(tmp.path() + "/clip"));
}

TEST(BadInput, RecordingRealDataWithoutSkeletonsNamesTheFlagToPass) {
  const std::string oni =
      std::string(REENACT_SOURCE_DIR) + "/../shared/data/oni/kinect-room-12f.oni";
  if (!std::filesystem::exists(oni)) GTEST_SKIP() << oni << " is absent (shared data)";
  TempDir tmp;
  const auto r = RunProcess({kCapture, "record", "--source", "oni:" + oni, "--out",
                             tmp.path() + "/clip"}, kQuick);
  // A real recording has no skeletons of its own: SLAM tracks it, but nothing can be stored
  // without a skeleton. The error says so on one line, names the flag, and leaves no clip.
  ExpectOneLineError(r, "has a skeleton; pass --skeleton");
  EXPECT_NE(r.err.find("oni:"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(tmp.path() + "/clip"));
}

TEST(BadInput, MissingSourceOptionIsUsageError) {
  TempDir tmp;
  const auto r = RunProcess({kCapture, "record", "--out", tmp.path() + "/clip"}, kQuick);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--source"), std::string::npos) << r.err;
}

TEST(BadInput, UnknownSourceKindFailsClearly) {
  TempDir tmp;
  const auto r = RunProcess({kCapture, "record", "--source", "webcam:0", "--out",
                             tmp.path() + "/clip"}, kQuick);
  ExpectOneLineError(r, "unknown source");
}

TEST(BadInput, BrowseWithServerDownFailsClearly) {
  const int port = testing::UnusedLoopbackPort();
  const auto r = RunProcess({kViewer, "browse", "--server", "http://127.0.0.1:" + std::to_string(port),
                             "--near", "48.1,11.5"}, kQuick);
  ExpectOneLineError(r, "cannot reach server");
}

TEST(BadInput, PlayWithServerDownFailsClearly) {
  TempDir tmp;
  const int port = testing::UnusedLoopbackPort();
  const auto r = RunProcess({kViewer, "play", "abc", "--server", "http://127.0.0.1:" + std::to_string(port),
                             "--headless", "--out", tmp.path() + "/out", "--cache", tmp.path() + "/c"},
                            kQuick);
  ExpectOneLineError(r, "cannot reach server");
}

// The texturing is checked before the server is contacted (none listens on port 1).
TEST(BadInput, UnknownTexturingListsTheKnownOnes) {
  TempDir tmp;
  for (const char* camera : {"orbit", "synthetic:turn-and-kick"}) {
    const auto r = RunProcess({kViewer, "play", "abc", "--server", "http://127.0.0.1:1", "--camera",
                               camera, "--texturing", "sharpest", "--headless", "--out",
                               tmp.path() + "/out"},
                              kQuick);
    ExpectOneLineError(r, "unknown texturing 'sharpest'; known: thesis, per-part, occlusion, blend, shape");
  }
}

// AR play: the viewer's camera is opened before the clip is fetched, so these need no server.
TEST(BadInput, ArCameraWithoutFramesFailsClearly) {
  TempDir tmp;
  std::filesystem::create_directories(tmp.path() + "/seq");
  std::ofstream(tmp.path() + "/seq/rgb.txt") << "# timestamp filename\n";
  const auto r = RunProcess(
      {kViewer, "play", "abc", "--server", "http://127.0.0.1:1", "--camera",
       "tum:" + tmp.path() + "/seq", "--calibration",
       std::string(REENACT_SOURCE_DIR) + "/docs/calibration/tum-fr1.yaml", "--headless", "--out",
       tmp.path() + "/out", "--cache", tmp.path() + "/c"},
      kQuick);
  ExpectOneLineError(r, "no frame");
}

TEST(BadInput, ArCameraWithoutCalibrationNamesTheFlag) {
  TempDir tmp;
  const auto r = RunProcess({kViewer, "play", "abc", "--server", "http://127.0.0.1:1", "--camera",
                             "video:" + tmp.path() + "/v.mp4", "--headless", "--out",
                             tmp.path() + "/out"},
                            kQuick);
  ExpectOneLineError(r, "--calibration");
}

TEST(BadInput, PublishWithServerDownFailsClearlyAndKeepsTheClip) {
  TempDir tmp;
  const std::string clip = tmp.path() + "/clip";
  const auto rec = RunProcess({kCapture, "record", "--source", "synthetic:turn-and-kick", "--out",
                               clip, "--frames", "3"}, std::chrono::seconds(120));
  ASSERT_EQ(rec.exit_code, 0) << rec.err;
  const int port = testing::UnusedLoopbackPort();
  const auto r = RunProcess({kCapture, "publish", clip, "--server",
                             "http://127.0.0.1:" + std::to_string(port), "--token", "t", "--lat",
                             "1", "--lon", "2"}, kQuick);
  ExpectOneLineError(r, "cannot reach server");
  const auto info = RunProcess({kCapture, "info", clip}, kQuick);
  EXPECT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("frames      3"), std::string::npos) << info.out;
}

TEST(BadInput, CorruptClipIsRefusedBeforeUpload) {
  TempDir tmp;
  const std::string clip = tmp.path() + "/clip";
  const auto rec = RunProcess({kCapture, "record", "--source", "synthetic:turn-and-kick", "--out",
                               clip, "--frames", "2"}, std::chrono::seconds(120));
  ASSERT_EQ(rec.exit_code, 0) << rec.err;
  {
    std::fstream f(clip + "/frames/000001.rfrm", std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(100);
    f.put('\x5a');
  }
  const int port = testing::UnusedLoopbackPort();
  const auto r = RunProcess({kCapture, "publish", clip, "--server",
                             "http://127.0.0.1:" + std::to_string(port), "--token", "t", "--lat",
                             "1", "--lon", "2"}, kQuick);
  EXPECT_NE(r.exit_code, 0);
  // The damaged frame is found before any byte is sent (so the down server never matters).
  EXPECT_NE(r.err.find("frame"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("cannot reach"), std::string::npos) << r.err;
}

TEST(BadInput, LatitudeOutOfRangeIsUsageError) {
  TempDir tmp;
  const auto r = RunProcess({kViewer, "browse", "--server", "http://127.0.0.1:1", "--near", "95,10"},
                            kQuick);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("latitude"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace reenact

namespace reenact {
namespace {

TEST(BadInput, RecordOntoAnExistingClipIsRefusedAndKeepsIt) {
  testing::TempDir tmp;
  const std::string clip = tmp.path() + "/clip";
  const auto first = testing::RunProcess({kCapture, "record", "--source", "synthetic:turn-and-kick",
                                          "--out", clip, "--frames", "2"},
                                         std::chrono::seconds(120));
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const auto second = testing::RunProcess({kCapture, "record", "--source", "synthetic:turn-and-kick",
                                           "--out", clip, "--frames", "3"},
                                          kQuick);
  ExpectOneLineError(second, "already exists");
  const auto info = testing::RunProcess({kCapture, "info", clip}, kQuick);
  EXPECT_NE(info.out.find("frames      2"), std::string::npos) << info.out;
}

}  // namespace
}  // namespace reenact
