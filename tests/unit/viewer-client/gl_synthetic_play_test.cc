// `play` over the synthetic viewer camera (viewer-client/camera/synthetic_camera_source.h) and
// a clip recorded from the same scenario through the real recording path: every camera frame
// must be posed, near the camera's true pose, and render.json must carry the truth beside the
// relocalised pose; the same in a window (ar_window_player.h) on a virtual X server (Xvfb),
// skipped where Xvfb is not installed. Needs OpenGL (EGL surfaceless); suites start with "Gl".
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "capture-client/record/clip_recorder.h"
#include "capture-client/source/synthetic_source.h"
#include "common/error/check.h"
#include "proto/clip/clip_directory.h"
#include "viewer-client/camera/synthetic_camera_source.h"
#include "viewer-client/play/ar_player.h"
#include "viewer-client/play/ar_window_player.h"

namespace reenact::viewer {
namespace {

namespace fs = std::filesystem;

struct Clip {
  Reenactment reenactment;
  proto::ClipMap map;
};

// The first 60 frames (2 s) of turn-and-kick, recorded and read back with its map.
Clip RecordClip(const fs::path& dir) {
  auto source = capture::SyntheticSource::Open("turn-and-kick");
  REENACT_CHECK(source.ok(), "synthetic source");
  capture::RecordOptions options;
  options.max_frames = 60;
  REENACT_CHECK(capture::RecordClip(**source, dir, options).ok(), "record");
  auto directory = proto::ReadClipDirectory(dir);
  REENACT_CHECK(directory.ok(), "read clip");
  std::vector<proto::ClipFrame> frames;
  for (int64_t n = 0; n < directory->manifest().frame_count; ++n)
    frames.push_back(directory->ReadFrame(n).value());
  return Clip{Reenactment(directory->manifest(), std::move(frames)), directory->ReadMap().value()};
}

Eigen::Isometry3d PoseFromJson(const nlohmann::json& j) {
  Eigen::Matrix4d m;
  for (int i = 0; i < 16; ++i) m(i / 4, i % 4) = j.at(i).get<double>();
  Eigen::Isometry3d pose;
  pose.matrix() = m;
  return pose;
}

TEST(GlSyntheticPlay, TracksEveryFrameNearTheTruth) {
  const fs::path dir =
      fs::temp_directory_path() / ("reenact-gl-synthetic-play-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  Clip clip = RecordClip(dir / "clip");
  // 40 frames from 0 to +45, back, to -45 degrees and back, the room alone.
  auto camera = OpenCameraSource("synthetic:turn-and-kick?frames=40", std::nullopt);
  ASSERT_TRUE(camera.ok()) << camera.error().message;
  ArPlayOptions options;
  options.out_dir = dir / "out";
  options.write_mp4 = false;
  auto summary = PlayArHeadless(clip.reenactment, std::move(clip.map), **camera, "clip", options);
  ASSERT_TRUE(summary.ok()) << summary.error().code << ": " << summary.error().message;
  EXPECT_EQ(summary->frames, 40);
  EXPECT_EQ(summary->lost, 0);
  EXPECT_EQ(summary->truth_frames, 40);
  // Near: a static sensor's map (all on the back wall) relocalises to a median 2.6 cm /
  // 0.26 degrees (docs/measurements.md; the 2 cm / 1 degree goal is not met yet), so
  // the bounds here are the relocaliser's accuracy with a margin; a wrong frame convention, an
  // inverted pose or the truth of another frame is tens of centimetres and degrees off.
  EXPECT_LT(summary->median_err_cm, 5.0);
  EXPECT_LT(summary->median_err_deg, 1.0);

  std::ifstream in(dir / "out" / "render.json");
  const nlohmann::json render = nlohmann::json::parse(in);
  ASSERT_EQ(render["frames"].size(), 40u);
  EXPECT_EQ(render["truth"]["frames"], 40);
  EXPECT_EQ(render["truth"]["within_2cm_1deg"], summary->within_2cm_1deg);
  // The clip's light (the scenario lights the subject, so one is found) as the viewer relit it.
  const SubjectLightFit& light = clip.reenactment.subject_light();
  ASSERT_TRUE(light.found);
  EXPECT_EQ(render["subject_light"]["found"], true);
  for (int i = 0; i < 3; ++i)
    EXPECT_DOUBLE_EQ(render["subject_light"]["light_in_world"][i].get<double>(), light.light[i]);
  EXPECT_DOUBLE_EQ(render["subject_light"]["strength"].get<double>(), light.light.norm());
  EXPECT_FALSE(render["subject_light"].contains("reason"));
  const SyntheticViewerPath path =
      MakeSyntheticViewerPath(capture::SyntheticScene::Create("turn-and-kick").value(), 40, 45);
  for (int k = 0; k < 40; ++k) {
    const nlohmann::json& f = render["frames"][k];
    ASSERT_FALSE(f["world_from_viewer"].is_null()) << k;
    const Eigen::Isometry3d truth = PoseFromJson(f["true_world_from_viewer"]);
    EXPECT_TRUE(truth.isApprox(path.world_from_viewer[k], 1e-9)) << k;
    const Eigen::Isometry3d estimate = PoseFromJson(f["world_from_viewer"]);
    const double cm = 100 * (estimate.translation() - truth.translation()).norm();
    EXPECT_NEAR(f["err_cm"].get<double>(), cm, 1e-6) << k;
    EXPECT_LT(cm, 10.0) << k;  // no frame far off
    EXPECT_LT(f["err_deg"].get<double>(), 2.0) << k;
  }
  fs::remove_all(dir);
}

// An Xvfb server on a display number nobody uses, DISPLAY pointing at it for the scope.
class VirtualDisplay {
 public:
  VirtualDisplay() {
    if (!fs::exists("/usr/bin/Xvfb")) return;
    for (int n = 100 + ::getpid() % 400, tries = 0; tries < 50; ++n, ++tries) {
      const std::string number = std::to_string(n);
      if (fs::exists("/tmp/.X" + number + "-lock") || fs::exists("/tmp/.X11-unix/X" + number))
        continue;
      pid_ = ::fork();
      if (pid_ == 0) {
        ::execl("/usr/bin/Xvfb", "Xvfb", (":" + number).c_str(), "-screen", "0", "1280x800x24",
                "-nolisten", "tcp", static_cast<char*>(nullptr));
        ::_exit(127);
      }
      // Ready when its socket appears (at most 10 s); gone if it exited (display taken).
      for (int wait = 0; wait < 200; ++wait) {
        if (fs::exists("/tmp/.X11-unix/X" + number)) {
          if (const char* old = std::getenv("DISPLAY")) saved_ = old;
          ::setenv("DISPLAY", (":" + number).c_str(), 1);
          ready_ = true;
          return;
        }
        if (::waitpid(pid_, nullptr, WNOHANG) == pid_) {
          pid_ = -1;
          break;
        }
        ::usleep(50'000);
      }
      Stop();
    }
  }
  ~VirtualDisplay() {
    Stop();
    if (saved_)
      ::setenv("DISPLAY", saved_->c_str(), 1);
    else if (ready_)
      ::unsetenv("DISPLAY");
  }
  bool ready() const { return ready_; }

 private:
  void Stop() {
    if (pid_ > 0 && ::kill(pid_, SIGTERM) == 0) ::waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }
  pid_t pid_ = -1;
  bool ready_ = false;
  std::optional<std::string> saved_;
};

TEST(GlSyntheticPlay, ShowsTheArViewInAWindow) {
  const VirtualDisplay display;
  if (!display.ready()) GTEST_SKIP() << "no Xvfb";
  const fs::path dir =
      fs::temp_directory_path() / ("reenact-gl-synthetic-window-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  Clip clip = RecordClip(dir / "clip");
  auto camera = OpenCameraSource("synthetic:turn-and-kick?frames=40", std::nullopt);
  ASSERT_TRUE(camera.ok()) << camera.error().message;
  ArWindowOptions options;
  options.max_frames = 25;  // stops before the camera ends
  auto shown = PlayArInWindow(clip.reenactment, std::move(clip.map), **camera, options);
  fs::remove_all(dir);
  ASSERT_TRUE(shown.ok()) << shown.error().code << ": " << shown.error().message;
  EXPECT_EQ(shown->frames, 25);
  EXPECT_EQ(shown->lost, 0);
  EXPECT_EQ(shown->relocalised + shown->tracked, 25);
  EXPECT_EQ(shown->truth_frames, 25);
  EXPECT_LT(shown->median_err_cm, 5.0);  // as in TracksEveryFrameNearTheTruth
  EXPECT_LT(shown->median_err_deg, 1.0);
  // The synthetic camera's frames are 1/30 s apart and shown no faster.
  EXPECT_GE(shown->seconds, 24 / 30.0);
}

TEST(GlSyntheticPlay, AWindowWithoutADisplayFailsClearly) {
  const char* old = std::getenv("DISPLAY");
  const std::optional<std::string> saved = old ? std::optional<std::string>(old) : std::nullopt;
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  const std::optional<std::string> saved_wayland =
      wayland ? std::optional<std::string>(wayland) : std::nullopt;
  ::unsetenv("DISPLAY");
  ::unsetenv("WAYLAND_DISPLAY");
  const fs::path dir =
      fs::temp_directory_path() / ("reenact-gl-synthetic-nodisplay-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  Clip clip = RecordClip(dir / "clip");
  fs::remove_all(dir);
  auto camera = OpenCameraSource("synthetic:turn-and-kick?frames=2", std::nullopt);
  ASSERT_TRUE(camera.ok());
  auto shown = PlayArInWindow(clip.reenactment, std::move(clip.map), **camera, {});
  if (saved) ::setenv("DISPLAY", saved->c_str(), 1);
  if (saved_wayland) ::setenv("WAYLAND_DISPLAY", saved_wayland->c_str(), 1);
  ASSERT_FALSE(shown.ok());
  EXPECT_EQ(shown.error().code, "no_display");
  EXPECT_NE(shown.error().message.find("--headless"), std::string::npos) << shown.error().message;
}

}  // namespace
}  // namespace reenact::viewer
