// A viewer far around the subject relocalises against a map with virtual views
// (capture-client/map/virtual_views.h) where the capture viewpoint's descriptors alone fail
// or nearly fail: the map is built as in relocaliser_test.cc, the truth comes by
// construction from the synthetic scene.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "capture-client/map/background_map_builder.h"
#include "capture-client/map/virtual_views.h"
#include "common/error/check.h"
#include "synthetic/synthetic_scene.h"
#include "viewer-client/play/orbit_camera.h"
#include "viewer-client/reloc/relocaliser.h"

namespace reenact::viewer {
namespace {

struct Maps {
  capture::SyntheticScene scene;
  proto::ClipMap plain, with_views;
  Eigen::Vector3d pivot;
};

// turn-and-kick (static sensor): keyframes 0, 30, ..., 150; virtual views from frames 0 and
// 90 at the default turns (+-20, +-40 degrees).
const Maps& TestMaps() {
  static const Maps maps = [] {
    auto scene = capture::SyntheticScene::Create("turn-and-kick");
    REENACT_CHECK(scene.ok(), "scene");
    capture::BackgroundMapBuilder builder;
    std::vector<capture::VirtualViewKeyframe> keyframes;
    for (int f = 0; f < scene->frame_count(); f += 30) {
      const capture::SyntheticView view = scene->RenderSensor(f);
      builder.AddKeyframe(view.color, view.depth, 0.001, view.mask, scene->sensor_camera(),
                          scene->world_from_sensor(f));
      if (f % 90 == 0) {
        keyframes.push_back({view.color, view.depth, view.mask, scene->world_from_sensor(f),
                             scene->skeleton_in_world(f)[Joint::kWaist]});
      }
    }
    proto::ClipMap plain = std::move(builder).Finish();
    proto::ClipMap with_views =
        capture::AddVirtualViews(plain, keyframes, 0.001, scene->sensor_camera(), scene->world_up(),
                                 capture::VirtualViewOptions{}, {});
    const Eigen::Vector3d pivot = scene->skeleton_in_world(0)[Joint::kTorso];
    return Maps{std::move(*scene), std::move(plain), std::move(with_views), pivot};
  }();
  return maps;
}

// The scene's frame `frame` seen from the orbit turned `angle_deg` about the subject (pivot),
// 5 cm above the sensor: the true pose and the grey image the relocaliser takes.
struct OrbitView {
  Eigen::Isometry3d world_from_viewer;
  cv::Mat gray;
};
OrbitView RenderOrbitView(const Maps& m, double angle_deg, int frame) {
  OrbitCameraOptions orbit;
  orbit.angle_deg = angle_deg;
  orbit.height_offset_m = 0.05;
  const auto truth =
      OrbitWorldFromViewer(m.scene.world_from_sensor(0), m.pivot, m.scene.world_up(), orbit);
  REENACT_CHECK(truth.has_value(), "the orbit camera cannot be placed");
  const capture::SyntheticView view = m.scene.Render(frame, m.scene.sensor_camera(), *truth);
  const cv::Mat rgb(view.color.height, view.color.width, CV_8UC3,
                    const_cast<uint8_t*>(view.color.data.data()));
  OrbitView out{*truth, {}};
  cv::cvtColor(rgb, out.gray, cv::COLOR_RGB2GRAY);
  return out;
}

TEST(RelocaliserVirtualViews, FarAroundTheSubjectTheViewsKeepTheViewerFound) {
  const Maps& m = TestMaps();
  ASSERT_GT(m.with_views.points.size(), 2 * m.plain.points.size());
  for (double angle : {-40.0, 40.0}) {
    const OrbitView view = RenderOrbitView(m, angle, 45);
    const cv::Mat& gray = view.gray;
    const Eigen::Isometry3d& truth = view.world_from_viewer;
    int inliers[2] = {0, 0};
    for (int with_views = 0; with_views <= 1; ++with_views) {
      auto reloc =
          Relocaliser::Create(with_views ? m.with_views : m.plain, m.scene.sensor_camera());
      ASSERT_TRUE(reloc.ok());
      const auto result = reloc->ProcessFrame(gray);
      ASSERT_TRUE(result.ok());
      if (!result->viewer_from_world) continue;
      inliers[with_views] = result->inliers;
      if (!with_views) continue;
      // The bounds of relocaliser_test.cc (4 cm, 0.5 degrees: twice what a least-squares fit
      // from the true matches lands at 20 degrees around).
      const Eigen::Isometry3d estimate = result->viewer_from_world->inverse();
      EXPECT_LT((estimate.translation() - truth.translation()).norm(), 0.04) << angle;
      EXPECT_LT(Eigen::AngleAxisd(truth.linear().transpose() * estimate.linear()).angle() * 180 /
                    std::numbers::pi,
                0.5)
          << angle;
    }
    // Measured while building this: lost at both turns with the capture's descriptors alone
    // (fewer than the 30 inliers the relocaliser needs), 91 and 102 inliers with the views.
    EXPECT_GE(inliers[1], 2 * std::max(inliers[0], 15))
        << angle << ": " << inliers[0] << " vs " << inliers[1];
  }
}

// What limits the pose far around the subject is each map point's own placement error (its
// keypoint as detected from the capture's or a virtual viewpoint, fixed per point), which
// averages out only over points (relocaliser.h). The default 2000 features per viewer frame
// must therefore find clearly more inliers than the map's own 1000 per view would, and with
// them a pose no worse on the whole. Truth: the orbit poses, by construction.
TEST(RelocaliserVirtualViews, MoreViewerFeaturesGiveMoreInliersFarAround) {
  const Maps& m = TestMaps();
  RelocaliserOptions fewer;
  fewer.features.num_features = 1000;
  ASSERT_GE(RelocaliserOptions{}.features.num_features, 2 * fewer.features.num_features);
  int inliers[2] = {0, 0};
  double squared_error_m2[2] = {0, 0};
  const std::vector<double> angles = {-45, -40, -35, 35, 40, 45};
  for (double angle : angles) {
    const OrbitView view = RenderOrbitView(m, angle, 30);
    const cv::Mat& gray = view.gray;
    const Eigen::Isometry3d& truth = view.world_from_viewer;
    for (int k = 0; k < 2; ++k) {
      auto reloc = Relocaliser::Create(m.with_views, m.scene.sensor_camera(),
                                       k == 0 ? fewer : RelocaliserOptions{});
      ASSERT_TRUE(reloc.ok());
      const auto result = reloc->ProcessFrame(gray);
      ASSERT_TRUE(result.ok());
      ASSERT_TRUE(result->viewer_from_world.has_value()) << angle << ": " << result->reason;
      inliers[k] += result->inliers;
      const Eigen::Isometry3d estimate = result->viewer_from_world->inverse();
      squared_error_m2[k] += (estimate.translation() - truth.translation()).squaredNorm();
      if (k == 1) {
        EXPECT_LT((estimate.translation() - truth.translation()).norm(), 0.04) << angle;
      }
    }
  }
  // Measured while building this: 423 inliers with 1000 features, 612 with 2000.
  EXPECT_GE(inliers[1], 1.3 * inliers[0]) << inliers[0] << " vs " << inliers[1];
  const double rms_cm[2] = {100 * std::sqrt(squared_error_m2[0] / angles.size()),
                            100 * std::sqrt(squared_error_m2[1] / angles.size())};
  EXPECT_LE(rms_cm[1], rms_cm[0]) << rms_cm[0] << " cm vs " << rms_cm[1] << " cm";
}

}  // namespace
}  // namespace reenact::viewer
