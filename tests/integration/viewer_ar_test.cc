// The viewer's AR play with the synthetic viewer camera as real processes: a clip recorded and
// published from the same scenario, played headless (render.json carries the truth beside
// each relocalised pose) and in a window on a virtual X server (Xvfb, where installed); and
// the bad input of the new flags and specs, each a one-line error and a non-zero exit.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>

#include "tests/integration/expect_error.h"
#include "tests/integration/process.h"

namespace reenact {
namespace {

using testing::BackgroundProcess;
using testing::ExpectOneLineError;
using testing::kBin;
using testing::kCapture;
using testing::kServer;
using testing::kViewer;
using testing::RunProcess;
using testing::TempDir;

const std::string kBench = kBin + "/tests/bench/reenact-bench";
constexpr auto kQuick = std::chrono::seconds(60);

std::string Field(const std::string& text, const std::string& pattern) {
  std::smatch m;
  return std::regex_search(text, m, std::regex(pattern)) ? m[1].str() : "";
}


TEST(ViewerAr, SyntheticCameraOverAPublishedClip) {
  TempDir tmp;
  BackgroundProcess server;
  const auto ready = server.Start(
      {kServer, "serve", "--db", tmp.path() + "/reenact.db", "--listen", "127.0.0.1:0"},
      "listening on ", std::chrono::seconds(20));
  ASSERT_TRUE(ready) << "server did not start: " << server.stderr_text();
  const std::string url = Field(*ready, R"((http://127\.0\.0\.1:\d+))");
  const auto user =
      RunProcess({kServer, "user", "add", "alice", "--db", tmp.path() + "/reenact.db"});
  ASSERT_EQ(user.exit_code, 0) << user.err;
  const std::string token = user.out.substr(0, user.out.find('\n'));
  const std::string clip_dir = tmp.path() + "/clip";
  const auto record = RunProcess({kCapture, "record", "--source", "synthetic:turn-and-kick",
                                  "--out", clip_dir, "--frames", "60", "--title", "Kick"},
                                 std::chrono::seconds(300));
  ASSERT_EQ(record.exit_code, 0) << record.err;
  const auto publish = RunProcess({kCapture, "publish", clip_dir, "--server", url, "--token", token,
                                   "--lat", "35.6595", "--lon", "139.7005"});
  ASSERT_EQ(publish.exit_code, 0) << publish.err;
  const std::string clip_id = Field(publish.out, R"(clip_id=(\S+))");
  ASSERT_FALSE(clip_id.empty()) << publish.out;

  const std::string out = tmp.path() + "/out";
  const std::string camera = "synthetic:turn-and-kick?frames=30";
  const auto play =
      RunProcess({kViewer, "play", clip_id, "--server", url, "--camera", camera, "--headless",
                  "--out", out, "--no-mp4", "--cache", tmp.path() + "/cache"},
                 std::chrono::seconds(300));
  ASSERT_EQ(play.exit_code, 0) << play.err;
  EXPECT_NE(play.out.find("0 lost"), std::string::npos) << play.out;
  EXPECT_NE(play.out.find("against the camera's true pose"), std::string::npos) << play.out;
  std::ifstream in(out + "/render.json");
  const nlohmann::json render = nlohmann::json::parse(in);
  EXPECT_EQ(render["presentation"], "ar");
  EXPECT_EQ(render["lost"], 0);
  EXPECT_EQ(render["truth"]["frames"], 30);
  // The relocaliser's accuracy on a static sensor's map with a margin (docs/measurements.md).
  EXPECT_LT(render["truth"]["median_err_cm"].get<double>(), 5.0);
  EXPECT_LT(render["truth"]["median_err_deg"].get<double>(), 1.0);
  for (const auto& f : render["frames"]) {
    ASSERT_EQ(f["true_world_from_viewer"].size(), 16u);
    EXPECT_LT(f["err_cm"].get<double>(), 10.0) << f["output"];
  }

  // The same in a window, where a virtual X server can be had.
  if (std::filesystem::exists("/usr/bin/xvfb-run")) {
    const auto shown =
        RunProcess({"/usr/bin/xvfb-run", "-a", "-s", "-screen 0 1280x800x24", kViewer, "play",
                    clip_id, "--server", url, "--camera", camera, "--cache", tmp.path() + "/cache"},
                   std::chrono::seconds(300));
    EXPECT_EQ(shown.exit_code, 0) << shown.err;
    EXPECT_NE(shown.out.find("showed 30 camera frames"), std::string::npos) << shown.out;
    EXPECT_NE(shown.out.find("0 lost"), std::string::npos) << shown.out;
  }
  EXPECT_EQ(server.Stop(), 0) << server.stderr_text();
}

// The camera is opened before the clip is fetched, so these need no server.
std::vector<std::string> Play(const std::vector<std::string>& more) {
  std::vector<std::string> argv = {kViewer, "play", "abc", "--server", "http://127.0.0.1:1"};
  argv.insert(argv.end(), more.begin(), more.end());
  return argv;
}

TEST(ViewerArBadInput, UnknownSyntheticScenarioListsTheKnownOnes) {
  TempDir tmp;
  ExpectOneLineError(RunProcess(Play({"--camera", "synthetic:no-such-scene", "--headless", "--out",
                                      tmp.path() + "/out"}),
                                kQuick),
                     "turn-and-kick");
}

TEST(ViewerArBadInput, SyntheticOptionOutOfRangeNamesIt) {
  TempDir tmp;
  ExpectOneLineError(RunProcess(Play({"--camera", "synthetic:turn-and-kick?max_deg=120",
                                      "--headless", "--out", tmp.path() + "/out"}),
                                kQuick),
                     "max_deg=120");
}

TEST(ViewerArBadInput, SyntheticCameraRefusesACalibration) {
  TempDir tmp;
  ExpectOneLineError(
      RunProcess(Play({"--camera", "synthetic:turn-and-kick", "--calibration",
                       tmp.path() + "/k.yaml", "--headless", "--out", tmp.path() + "/out"}),
                 kQuick),
      "drop --calibration");
}

TEST(ViewerArBadInput, WindowRefusesHeadlessOnlyFlags) {
  TempDir tmp;
  ExpectOneLineError(
      RunProcess(Play({"--camera", "synthetic:turn-and-kick", "--out", tmp.path() + "/out"}),
                 kQuick),
      "--out is for --headless");
  ExpectOneLineError(
      RunProcess(Play({"--camera", "synthetic:turn-and-kick", "--clip-clock", "frames"}), kQuick),
      "--clip-clock is for --headless");
}

TEST(BenchViewerBadInput, FlagsOutOfRange) {
  ExpectOneLineError(RunProcess({kBench, "viewer", "--repeats", "0"}, kQuick), "--repeats");
  ExpectOneLineError(RunProcess({kBench, "viewer", "--frames", "1"}, kQuick), "--frames");
  ExpectOneLineError(RunProcess({kBench, "viewer", "--frames", "many"}, kQuick), "frames");
  ExpectOneLineError(RunProcess({kBench, "viewer", "--texturing", "nope"}, kQuick),
                     "unknown texturing 'nope'");
}

}  // namespace
}  // namespace reenact
