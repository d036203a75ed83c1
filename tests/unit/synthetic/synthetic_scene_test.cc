#include "synthetic/synthetic_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>

#include "common/error/check.h"
#include "synthetic/scenario.h"

namespace reenact::capture {
namespace {

const SyntheticScene& Scene() {
  static const SyntheticScene scene = SyntheticScene::Create("turn-and-kick", 3).value();
  return scene;
}

// Ray through a pixel centre in the world frame: origin and a direction whose camera-z
// component is 1 (so the ray parameter is the camera depth).
struct Ray {
  Eigen::Vector3d origin, direction;
};
Ray PixelRay(const PinholeCamera& c, const Eigen::Isometry3d& world_from_camera, int x, int y) {
  const Eigen::Vector3d d((x - c.cx) / c.fx, (y - c.cy) / c.fy, 1.0);
  return {world_from_camera.translation(), world_from_camera.linear() * d};
}

TEST(SyntheticScene, UnknownScenarioListsTheKnownOnes) {
  const auto scene = SyntheticScene::Create("moonwalk");
  ASSERT_FALSE(scene.ok());
  EXPECT_EQ(scene.error().code, "not_found");
  for (const std::string& name : SyntheticScene::ScenarioNames())
    EXPECT_NE(scene.error().message.find(name), std::string::npos) << name;
  EXPECT_NE(scene.error().message.find("moonwalk"), std::string::npos);
}

TEST(SyntheticScene, TurnAndKickTiming) {
  const SyntheticScene& s = Scene();
  EXPECT_DOUBLE_EQ(s.frame_rate_hz(), 30.0);
  EXPECT_NEAR(s.frame_count() / s.frame_rate_hz(), 6.0, 0.5);
  EXPECT_EQ(s.sensor_camera().width, 640);
  EXPECT_EQ(s.sensor_camera().height, 480);
  EXPECT_EQ(s.world_up(), Eigen::Vector3d::UnitZ());
}

TEST(SyntheticScene, SensorIsInFrontOfTheSubjectAndLooksAtIt) {
  const SyntheticScene& s = Scene();
  const Eigen::Isometry3d sensor = s.world_from_sensor(0);
  const Skeleton sk = s.skeleton_in_world(0);
  const Eigen::Vector3d eye = sensor.translation();
  EXPECT_GE(eye.z(), 1.2);
  EXPECT_LE(eye.z(), 1.4);
  const Eigen::Vector3d to_subject = sk[Joint::kWaist] - eye;
  EXPECT_GE(to_subject.head<2>().norm(), 2.8);
  EXPECT_LE(to_subject.head<2>().norm(), 3.2);
  // The optical axis (camera z) points at the subject within 10 degrees.
  const Eigen::Vector3d axis = sensor.linear().col(2);
  EXPECT_GT(axis.dot(to_subject.normalized()), std::cos(10 * std::numbers::pi / 180));
  EXPECT_TRUE(sensor.linear().isUnitary(1e-9));
  EXPECT_NEAR(sensor.linear().determinant(), 1.0, 1e-9);
  // Image "down" (camera y) points downwards in the world.
  EXPECT_LT(sensor.linear().col(1).z(), 0);
}

TEST(SyntheticScene, SameSeedGivesIdenticalImages) {
  const SyntheticScene a = SyntheticScene::Create("turn-and-kick", 9).value();
  const SyntheticScene b = SyntheticScene::Create("turn-and-kick", 9).value();
  const SyntheticScene c = SyntheticScene::Create("turn-and-kick", 10).value();
  SyntheticRenderOptions noisy;
  noisy.depth_noise = true;
  const SyntheticView va = a.RenderSensor(37, noisy), vb = b.RenderSensor(37, noisy);
  const SyntheticView vc = c.RenderSensor(37, noisy);
  EXPECT_EQ(va.color.data, vb.color.data);
  EXPECT_EQ(va.depth.data, vb.depth.data);
  EXPECT_EQ(va.mask.data, vb.mask.data);
  EXPECT_EQ(va.part_labels.data, vb.part_labels.data);
  EXPECT_NE(va.depth.data, vc.depth.data);  // the seed drives the noise
  EXPECT_EQ(va.color.data, vc.color.data);
}

TEST(SyntheticScene, SkeletonProjectsInsideTheMask) {
  const SyntheticScene& s = Scene();
  const PinholeCamera& cam = s.sensor_camera();
  for (int frame = 0; frame < s.frame_count(); frame += 9) {
    const SyntheticView view = s.RenderSensor(frame);
    const Skeleton sk =
        s.skeleton_in_world(frame).Transformed(s.world_from_sensor(frame).inverse());
    for (int j = 0; j < kJointCount; ++j) {
      EXPECT_DOUBLE_EQ(sk.confidence[j], 1.0);
      const auto px = cam.Project(sk.position[j]);
      ASSERT_TRUE(px.has_value());
      const int x = static_cast<int>(std::lround(px->x())),
                y = static_cast<int>(std::lround(px->y()));
      ASSERT_TRUE(view.mask.Contains(x, y));
      EXPECT_EQ(view.mask.at(x, y), 255)
          << "frame " << frame << " joint " << JointName(static_cast<Joint>(j));
    }
  }
}

TEST(SyntheticScene, LabelsAgreeWithTheMask) {
  const SyntheticScene& s = Scene();
  for (int frame : {0, 80, 130}) {
    const SyntheticView view = s.RenderSensor(frame);
    std::set<int> seen;
    for (size_t i = 0; i < view.mask.data.size(); ++i) {
      const int label = view.part_labels.data[i];
      ASSERT_TRUE(view.mask.data[i] == 0 || view.mask.data[i] == 255);
      EXPECT_EQ(label != kBackgroundLabel, view.mask.data[i] == 255);
      EXPECT_LE(label, kBodyPartCount);
      if (label != kBackgroundLabel) seen.insert(label);
    }
    if (frame == 0) {
      EXPECT_EQ(seen.size(), static_cast<size_t>(kBodyPartCount));
    }
  }
}

TEST(SyntheticScene, BoneMidpointsCarryTheirPartLabelInTheCalibrationPose) {
  const SyntheticScene& s = Scene();
  const SyntheticView view = s.RenderSensor(0);
  const Skeleton sk = s.skeleton_in_world(0).Transformed(s.world_from_sensor(0).inverse());
  for (int p = 0; p < kBodyPartCount; ++p) {
    const BodyPart part = static_cast<BodyPart>(p);
    const auto [a, b] = PartJoints(part);
    const auto px = s.sensor_camera().Project(0.5 * (sk[a] + sk[b]));
    ASSERT_TRUE(px.has_value());
    EXPECT_EQ(view.part_labels.at(static_cast<int>(std::lround(px->x())),
                                  static_cast<int>(std::lround(px->y()))),
              PartLabel(part))
        << PartName(part);
  }
}

TEST(SyntheticScene, FloorAndBackWallDepthMatchPlaneGeometry) {
  const SyntheticScene& s = Scene();
  const PinholeCamera& cam = s.sensor_camera();
  const Eigen::Isometry3d world_from_sensor = s.world_from_sensor(0);
  const SyntheticView view = s.RenderSensor(0);
  int floor_checked = 0, wall_checked = 0;
  for (int y = 0; y < cam.height; y += 5)
    for (int x = 0; x < cam.width; x += 5) {
      if (view.mask.at(x, y) != 0) continue;
      const Ray ray = PixelRay(cam, world_from_sensor, x, y);
      // Floor z = 0, away from the furniture.
      if (ray.direction.z() < 0) {
        const double t = -ray.origin.z() / ray.direction.z();
        const Eigen::Vector3d hit = ray.origin + t * ray.direction;
        if (std::abs(hit.x()) < 1.5 && hit.y() > -2.5 && hit.y() < 1.5) {
          EXPECT_NEAR(view.depth.at(x, y), t * 1000.0, 1.0) << x << "," << y;
          ++floor_checked;
        }
      }
      // Back wall y = 2.5, above the furniture and below the ceiling.
      if (ray.direction.y() > 0) {
        const double t = (2.5 - ray.origin.y()) / ray.direction.y();
        const Eigen::Vector3d hit = ray.origin + t * ray.direction;
        if (std::abs(hit.x()) < 2.5 && hit.z() > 2.0 && hit.z() < 2.9) {
          EXPECT_NEAR(view.depth.at(x, y), t * 1000.0, 1.0) << x << "," << y;
          ++wall_checked;
        }
      }
    }
  EXPECT_GT(floor_checked, 500);
  EXPECT_GT(wall_checked, 500);
}

TEST(SyntheticScene, WithoutTheRoomOnlyTheSubjectHasDepth) {
  const SyntheticScene& s = Scene();
  SyntheticRenderOptions options;
  options.draw_room = false;
  const SyntheticView view = s.RenderSensor(10, options);
  int subject = 0;
  for (size_t i = 0; i < view.depth.data.size(); ++i) {
    EXPECT_EQ(view.depth.data[i] != 0, view.mask.data[i] == 255);
    if (view.mask.data[i] == 255) {
      ++subject;
      // The subject stands about 3 m from the sensor.
      EXPECT_GT(view.depth.data[i], 2400);
      EXPECT_LT(view.depth.data[i], 3500);
    }
  }
  EXPECT_GT(subject, 5000);
}

TEST(SyntheticScene, DepthNoiseFollowsTheKinectModel) {
  const SyntheticScene& s = Scene();
  SyntheticRenderOptions noisy;
  noisy.depth_noise = true;
  noisy.noise.shadow_holes = false;  // the noise alone; the holes: depth_noise_test.cc
  const SyntheticView clean = s.RenderSensor(0), view = s.RenderSensor(0, noisy);
  EXPECT_EQ(clean.mask.data, view.mask.data);
  double sum2 = 0;
  int n = 0;
  for (size_t i = 0; i < clean.depth.data.size(); ++i) {
    EXPECT_EQ(clean.depth.data[i] == 0, view.depth.data[i] == 0);
    const double z = clean.depth.data[i] * 1e-3;
    if (z > 2.9 && z < 3.1) {
      const double e = (view.depth.data[i] - clean.depth.data[i]) * 1e-3;
      sum2 += e * e;
      ++n;
    }
  }
  ASSERT_GT(n, 1000);
  // sigma = 1.425e-3 z^2 plus disparity steps of 2.85e-3 z^2 (uniform: step / sqrt(12)).
  const double sigma = std::hypot(1.425e-3 * 9, 2.85e-3 * 9 / std::sqrt(12.0));
  EXPECT_NEAR(std::sqrt(sum2 / n), sigma, 0.3 * sigma);
}

TEST(SyntheticScene, RendersFromAnyCamera) {
  const SyntheticScene& s = Scene();
  PinholeCamera cam = PinholeCamera::KinectLike().Cropped(0, 0, 320, 240);
  cam.cx = 160;
  cam.cy = 120;
  cam.fx = cam.fy = 250;
  const Eigen::Isometry3d world_from_camera =
      LookAt(Eigen::Vector3d(2.4, 1.5, 1.7), Eigen::Vector3d(0, 0, 1.0));
  const SyntheticView view = s.Render(20, cam, world_from_camera);
  EXPECT_EQ(view.color.width, 320);
  const Skeleton sk = s.skeleton_in_world(20).Transformed(world_from_camera.inverse());
  for (Joint j : {Joint::kHead, Joint::kTorso, Joint::kWaist, Joint::kLeftKnee}) {
    const auto px = cam.Project(sk[j]);
    ASSERT_TRUE(px.has_value());
    EXPECT_EQ(view.mask.at(static_cast<int>(std::lround(px->x())),
                           static_cast<int>(std::lround(px->y()))),
              255)
        << JointName(j);
  }
}

TEST(SyntheticScene, BadInputIsRejected) {
  const SyntheticScene& s = Scene();
  EXPECT_THROW(s.RenderSensor(s.frame_count()), CheckError);
  EXPECT_THROW(s.skeleton_in_world(-1), CheckError);
  SyntheticRenderOptions bad;
  bad.min_depth_m = 9;
  EXPECT_THROW(s.RenderSensor(0, bad), CheckError);
  PinholeCamera distorted = s.sensor_camera();
  distorted.distortion.k1 = 0.2;
  EXPECT_THROW(s.Render(0, distorted, s.world_from_sensor(0)), CheckError);
}

}  // namespace
}  // namespace reenact::capture
