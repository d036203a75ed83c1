// The three programs as separate processes over loopback HTTP: server, capture + publish,
// browse + play headless; the rendered subject is checked against the synthetic scene's
// ground truth seen from the very same novel viewpoint.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <regex>

#include "synthetic/synthetic_scene.h"
#include "tests/integration/process.h"

namespace reenact {
namespace {

using testing::BackgroundProcess;
using testing::RunProcess;
using testing::TempDir;

using testing::kCapture;
using testing::kServer;
using testing::kViewer;

std::string Field(const std::string& text, const std::string& pattern) {
  std::smatch m;
  return std::regex_search(text, m, std::regex(pattern)) ? m[1].str() : "";
}

Eigen::Isometry3d PoseFromJson(const nlohmann::json& j) {
  Eigen::Matrix4d m;
  for (int i = 0; i < 16; ++i) m(i / 4, i % 4) = j.at(i).get<double>();
  Eigen::Isometry3d pose;
  pose.matrix() = m;
  return pose;
}

TEST(EndToEnd, PublishBrowseAndPlayMatchesGroundTruthAtNovelViewpoint) {
  TempDir tmp;
  BackgroundProcess server;
  const auto ready = server.Start(
      {kServer, "serve", "--db", tmp.path() + "/reenact.db", "--listen", "127.0.0.1:0"},
      "listening on ", std::chrono::seconds(20));
  ASSERT_TRUE(ready) << "server did not start: " << server.stderr_text();
  const std::string url = Field(*ready, R"((http://127\.0\.0\.1:\d+))");
  ASSERT_FALSE(url.empty()) << *ready;

  const auto user =
      RunProcess({kServer, "user", "add", "alice", "--db", tmp.path() + "/reenact.db"});
  ASSERT_EQ(user.exit_code, 0) << user.err;
  const std::string token = user.out.substr(0, user.out.find('\n'));  // the token alone
  ASSERT_FALSE(token.empty()) << user.out;

  const std::string clip_dir = tmp.path() + "/clip";
  const auto record = RunProcess({kCapture, "record", "--source", "synthetic:turn-and-kick",
                                  "--out", clip_dir, "--title", "Turn and kick"},
                                 std::chrono::seconds(300));
  ASSERT_EQ(record.exit_code, 0) << record.err;

  const auto publish = RunProcess({kCapture, "publish", clip_dir, "--server", url, "--token", token,
                                   "--lat", "35.6595", "--lon", "139.7005"});
  ASSERT_EQ(publish.exit_code, 0) << publish.err;
  const std::string clip_id = Field(publish.out, R"(clip_id=(\S+))");
  ASSERT_FALSE(clip_id.empty()) << publish.out;

  const auto browse = RunProcess({kViewer, "browse", "--server", url, "--near", "35.6596,139.7006",
                                  "--radius-m", "100", "--json"});
  ASSERT_EQ(browse.exit_code, 0) << browse.err;
  const auto listing = nlohmann::json::parse(browse.out);
  ASSERT_EQ(listing.size(), 1u);
  EXPECT_EQ(listing[0]["id"], clip_id);
  EXPECT_LT(listing[0]["distance_m"].get<double>(), 20.0);  // ~14 m by the haversine formula

  const std::string out = tmp.path() + "/out";
  const auto play =
      RunProcess({kViewer, "play", clip_id, "--server", url, "--camera", "orbit", "--orbit-deg",
                  "60", "--headless", "--out", out, "--masks", "--cache", tmp.path() + "/cache"},
                 std::chrono::seconds(300));
  ASSERT_EQ(play.exit_code, 0) << play.err;
  EXPECT_EQ(server.Stop(), 0) << "server did not stop cleanly: " << server.stderr_text();
  // The default texturing relights: the scenario lights its subject, so the light is found and
  // the viewer says so, and render.json records it.
  EXPECT_NE(play.out.find("relighting under the clip's light: strength"), std::string::npos)
      << play.out;

  std::ifstream render_file(out + "/render.json");
  ASSERT_TRUE(render_file) << "render.json missing";
  const auto render = nlohmann::json::parse(render_file);
  PinholeCamera camera;
  camera.width = render["camera"]["width"];
  camera.height = render["camera"]["height"];
  camera.fx = render["camera"]["fx"];
  camera.fy = render["camera"]["fy"];
  camera.cx = render["camera"]["cx"];
  camera.cy = render["camera"]["cy"];
  const Eigen::Isometry3d world_from_viewer = PoseFromJson(render["world_from_viewer"]);
  EXPECT_EQ(render["subject_light"]["found"], true);
  EXPECT_GT(render["subject_light"]["strength"].get<double>(), 0.0);

  // The viewpoint really is novel: at least 45 degrees around the subject (about world_up)
  // from the capture sensor.
  const auto scene = capture::SyntheticScene::Create("turn-and-kick");
  ASSERT_TRUE(scene.ok());
  const Eigen::Vector3d up = scene->world_up();
  auto horizontal = [&](Eigen::Vector3d v) { return Eigen::Vector3d(v - v.dot(up) * up); };
  const Eigen::Vector3d centre = scene->skeleton_in_world(0)[Joint::kWaist];
  const Eigen::Vector3d a = horizontal(scene->world_from_sensor(0).translation() - centre);
  const Eigen::Vector3d b = horizontal(world_from_viewer.translation() - centre);
  EXPECT_GE(std::acos(a.normalized().dot(b.normalized())) * 180 / M_PI, 45.0);

  double iou_sum = 0, colour_error_sum = 0;
  int checked = 0;
  const auto& frames = render["frames"];
  ASSERT_EQ(static_cast<int>(frames.size()), scene->frame_count());
  for (size_t i = 0; i < frames.size(); i += 10) {
    const int k = frames[i]["clip_frame"];
    const cv::Mat mask = cv::imread(out + "/frames/mask_" + cv::format("%04d", int(i)) + ".png",
                                    cv::IMREAD_GRAYSCALE);
    const cv::Mat colour =
        cv::imread(out + "/" + frames[i]["file"].get<std::string>(), cv::IMREAD_COLOR);
    ASSERT_FALSE(mask.empty());
    ASSERT_FALSE(colour.empty());
    const capture::SyntheticView truth =
        scene->Render(k, camera, world_from_viewer, {.draw_room = false});
    int inter = 0, uni = 0, pixels = 0;
    double colour_error = 0;
    for (int y = 0; y < camera.height; ++y)
      for (int x = 0; x < camera.width; ++x) {
        const bool r = mask.at<uint8_t>(y, x) > 127, t = truth.mask.at(x, y) > 127;
        inter += r && t;
        uni += r || t;
        if (r && t) {
          const cv::Vec3b bgr = colour.at<cv::Vec3b>(y, x);
          for (int c = 0; c < 3; ++c)
            colour_error += std::abs(bgr[2 - c] - truth.color.at(x, y, c));
          pixels += 3;
        }
      }
    ASSERT_GT(uni, 0);
    iou_sum += static_cast<double>(inter) / uni;
    if (pixels) colour_error_sum += colour_error / pixels;
    ++checked;
  }
  const double mean_iou = iou_sum / checked, mean_colour_error = colour_error_sum / checked;
  RecordProperty("mean_iou", std::to_string(mean_iou));
  RecordProperty("mean_colour_error", std::to_string(mean_colour_error));
  std::printf(
      "novel view 60 deg: mean silhouette IoU %.3f, mean abs colour error %.1f / 255 "
      "over %d frames\n",
      mean_iou, mean_colour_error, checked);
  // Issue bound: a cylinder model of a tapered body keeps the silhouette IoU >= 0.7.
  EXPECT_GE(mean_iou, 0.7);
  // Colour: where both silhouettes agree the texture should come from the same body surface;
  // misregistration at part borders and JPEG keep it above 0, but a wrong texture (wrong
  // side of the body: shirt front vs back, skin vs cloth) differs by 60-150 levels.
  EXPECT_LT(mean_colour_error, 40.0);
}

}  // namespace
}  // namespace reenact
