// The static scene learned beside the person: counted once per frame, never from readings near
// the fitted body or the floor, forgotten where seen through, and its points dropped from an
// observation. The scene is built by hand on the detector's grid: a wall 4 m away, a box face
// beside the capsule body standing 2.5 m in front of a level Kinect-like sensor.
#include "capture-client/tracker/static_scene_voxels.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/error/check.h"
#include "tests/unit/capture-client/tracker/capsule_body_scene.h"

namespace reenact::capture {
namespace {

using tracker_test::FacingSensor;

constexpr int kStep = 2;        // grid pixels
constexpr double kBodyZ = 2.5;  // the body's waist depth
constexpr double kWallZ = 4.0;
// The box face: 0.65-0.8 m right of the body's axis (0.3 m beyond the hand's surface, within
// see_through_margin_m of the body), at the body's depth.
constexpr double kBoxX0 = 0.65, kBoxX1 = 0.8, kBoxZ = kBodyZ;

struct Scene {
  PinholeCamera camera = PinholeCamera::KinectLike();
  PixelRays rays{camera};
  ArticulatedBody body{BodyShape::FromHeight(1.75)};
  PosedBody3 posed = body.Pose(FacingSensor(body, kBodyZ));
  // A sensor placed and turned in the world, so that the map's frame is not the sensor's.
  Eigen::Isometry3d world_from_sensor =
      Eigen::Translation3d(1.0, -2.0, 0.5) *
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.2, 1, 0.1).normalized());

  // The grid readings: the wall, the box face unless `box` is false; no person mask (the
  // body's own pixels are the wall's: readings near the body are tested separately).
  PersonBlob Blob(bool box = true) const {
    PersonBlob blob;
    blob.status = DetectStatus::kOk;
    blob.grid_step_px = kStep;
    const int gw = camera.width / kStep, gh = camera.height / kStep;
    blob.mask = ImageGray8(gw, gh, 1, 0);
    blob.depth_m = Image<float>(gw, gh, 1, static_cast<float>(kWallZ));
    if (box)
      for (int y = 0; y < gh; ++y)
        for (int x = 0; x < gw; ++x)
          if (InBox(x, y)) blob.depth_m.at(x, y) = static_cast<float>(kBoxZ);
    return blob;
  }
  bool InBox(int x, int y) const {
    const Eigen::Vector3d ray = camera.Unproject(Eigen::Vector2d(x * kStep, y * kStep), kBoxZ);
    return ray.x() >= kBoxX0 && ray.x() <= kBoxX1 && ray.y() >= 0.4 && ray.y() <= 1.2;
  }
  // The reading of grid pixel (x, y) at depth z, sensor frame, and that of the grid pixel
  // nearest a point.
  Eigen::Vector3d Reading(int x, int y, double z) const {
    return camera.Unproject(Eigen::Vector2d(x * kStep, y * kStep), z);
  }
  Eigen::Vector3d ReadingAt(const Eigen::Vector3d& p, int dx = 0, int dy = 0) const {
    const Eigen::Vector2d px = *camera.Project(p) / kStep;
    return Reading(static_cast<int>(std::lround(px.x())) + dx,
                   static_cast<int>(std::lround(px.y())) + dy, p.z());
  }
  // Sets the readings of the (2 half + 1)^2 grid pixels around p's to p's depth, and counts
  // those of them that `map` holds static.
  void PutPatch(const Eigen::Vector3d& p, int half, PersonBlob* blob) const {
    for (int dy = -half; dy <= half; ++dy)
      for (int dx = -half; dx <= half; ++dx) {
        const Eigen::Vector2d px = *camera.Project(ReadingAt(p, dx, dy)) / kStep;
        blob->depth_m.at(static_cast<int>(std::lround(px.x())),
                         static_cast<int>(std::lround(px.y()))) = static_cast<float>(p.z());
      }
  }
  int StaticInPatch(const StaticSceneVoxels& map, const Eigen::Vector3d& p, int half) const {
    int n = 0;
    for (int dy = -half; dy <= half; ++dy)
      for (int dx = -half; dx <= half; ++dx)
        n += map.IsStatic(world_from_sensor * ReadingAt(p, dx, dy));
    return n;
  }
  // A reading near the box face's centre, in the world.
  Eigen::Vector3d BoxCentre() const {
    return world_from_sensor * ReadingAt(Eigen::Vector3d(0.5 * (kBoxX0 + kBoxX1), 0.8, kBoxZ));
  }
};

TEST(StaticSceneVoxels, CountsEachFrameOnceUntilMinFrames) {
  // The box face fills many grid pixels per voxel; counted per reading, one frame would do.
  const Scene s;
  StaticSceneOptions options;
  StaticSceneVoxels map(s.camera, options);
  const PersonBlob blob = s.Blob();
  for (int f = 1; f < options.min_frames; ++f)
    map.Learn(blob, s.rays, s.world_from_sensor, s.body, s.posed);
  EXPECT_FALSE(map.IsStatic(s.BoxCentre()));
  map.Learn(blob, s.rays, s.world_from_sensor, s.body, s.posed);
  EXPECT_TRUE(map.IsStatic(s.BoxCentre()));
  // In the world frame: the same point in the sensor frame is elsewhere in the world.
  EXPECT_FALSE(map.IsStatic(s.world_from_sensor.inverse() * s.BoxCentre()));
}

TEST(StaticSceneVoxels, NeverLearnsReadingsNearTheFittedBody) {
  // A patch 8 cm in front of the chest's surface (outside the person's mask: a part the
  // detector left out) stays the person's; one 0.9 m in front of the body is the scene's.
  const Scene s;
  StaticSceneOptions options;
  options.learn_step = 1;  // every reading of the patches
  StaticSceneVoxels map(s.camera, options);
  PersonBlob blob = s.Blob(false);
  const Eigen::Vector3d chest = s.posed.skeleton[Joint::kTorso];
  const Eigen::Vector3d near(chest.x(), chest.y(), chest.z() - s.body.shape().torso_radius - 0.08);
  const Eigen::Vector3d far(chest.x(), chest.y() + 0.3, chest.z() - 0.9);
  s.PutPatch(near, 3, &blob);
  s.PutPatch(far, 3, &blob);
  for (int f = 0; f < 20; ++f) map.Learn(blob, s.rays, s.world_from_sensor, s.body, s.posed);
  EXPECT_EQ(s.StaticInPatch(map, near, 3), 0);
  EXPECT_EQ(s.StaticInPatch(map, far, 3), 49);
}

TEST(StaticSceneVoxels, NeverLearnsTheFloor) {
  // Readings 3 cm above the detector's floor (a foot's lowest points would share their
  // voxels) are not learned; those 30 cm above it are.
  const Scene s;
  StaticSceneOptions options;
  options.learn_step = 1;
  StaticSceneVoxels map(s.camera, options);
  PersonBlob blob = s.Blob(false);
  blob.floor_in_sensor = tracker_test::LevelFloor();
  const double floor_y = tracker_test::kSensorHeight;
  const Eigen::Vector3d low(-0.8, floor_y - 0.03, 3.5), high(-0.8, floor_y - 0.3, 3.5);
  s.PutPatch(low, 2, &blob);
  s.PutPatch(high, 2, &blob);
  for (int f = 0; f < 12; ++f) map.Learn(blob, s.rays, s.world_from_sensor, s.body, s.posed);
  EXPECT_EQ(s.StaticInPatch(map, low, 2), 0);
  EXPECT_EQ(s.StaticInPatch(map, high, 2), 25);
}

TEST(StaticSceneVoxels, DropsAnObjectsLowestPointsByTheVoxelAboveThem) {
  // A box face standing on the floor, 3.5 m away: its lowest centimetres are not learned,
  // but a point there is dropped by the static voxel above it (the floor given); a point as
  // low beside it, under no static voxel (a foot), is kept.
  const Scene s;
  StaticSceneOptions options;
  options.learn_step = 1;
  StaticSceneVoxels map(s.camera, options);
  PersonBlob blob = s.Blob(false);
  blob.floor_in_sensor = tracker_test::LevelFloor();
  const double floor_y = tracker_test::kSensorHeight, z = 3.5;
  for (int y = 0; y < blob.depth_m.height; ++y)
    for (int x = 0; x < blob.depth_m.width; ++x) {
      const Eigen::Vector3d r = s.Reading(x, y, z);
      if (r.x() >= -1.0 && r.x() <= -0.7 && r.y() >= floor_y - 0.4 && r.y() <= floor_y)
        blob.depth_m.at(x, y) = static_cast<float>(z);
    }
  for (int f = 0; f < 12; ++f) map.Learn(blob, s.rays, s.world_from_sensor, s.body, s.posed);
  const Eigen::Vector3d down(0, 1, 0);
  const double lift = options.floor_clearance_m - 0.03 + 0.5 * options.voxel_m;
  const Eigen::Vector3d above = s.ReadingAt(Eigen::Vector3d(-0.85, floor_y - 0.03 - lift, z));
  ASSERT_TRUE(map.IsStatic(s.world_from_sensor * above));
  const Eigen::Vector3d box_low = above + lift * down;
  const Eigen::Vector3d foot(0.9, floor_y - 0.03, z);
  BodyObservation obs;
  obs.points = {box_low, foot};
  EXPECT_EQ(map.DropStatic(s.world_from_sensor, std::nullopt, &obs), 0);
  EXPECT_EQ(map.DropStatic(s.world_from_sensor, blob.floor_in_sensor, &obs), 1);
  ASSERT_EQ(obs.points.size(), 1u);
  EXPECT_EQ(obs.points[0], foot);
}

TEST(StaticSceneVoxels, ForgetsAnObjectSeenThroughNearThePerson) {
  const Scene s;
  StaticSceneVoxels map(s.camera, StaticSceneOptions{});
  for (int f = 0; f < 12; ++f) map.Learn(s.Blob(), s.rays, s.world_from_sensor, s.body, s.posed);
  ASSERT_TRUE(map.IsStatic(s.BoxCentre()));
  // The box taken away: the wall is seen where it stood, 1.5 m behind.
  map.Learn(s.Blob(false), s.rays, s.world_from_sensor, s.body, s.posed);
  EXPECT_FALSE(map.IsStatic(s.BoxCentre()));
}

TEST(StaticSceneVoxels, DropsTheScenesPointsAndKeepsThePersons) {
  const Scene s;
  StaticSceneVoxels map(s.camera, StaticSceneOptions{});
  for (int f = 0; f < 12; ++f) map.Learn(s.Blob(), s.rays, s.world_from_sensor, s.body, s.posed);
  // Five of the box's readings, and five points on the chest's surface (where the wall's
  // readings lay behind the body: never the scene's).
  BodyObservation obs;
  const Eigen::Vector3d box(0.5 * (kBoxX0 + kBoxX1), 0.8, kBoxZ);
  const Eigen::Vector3d chest =
      s.posed.skeleton[Joint::kTorso] - Eigen::Vector3d(0, 0, s.body.shape().torso_radius);
  for (int k = 0; k < 5; ++k) {
    obs.points.push_back(s.ReadingAt(box, 0, 3 * k));
    obs.points.push_back(chest + Eigen::Vector3d(0, 0.05 * k, 0));
  }
  EXPECT_EQ(map.DropStatic(s.world_from_sensor, std::nullopt, &obs), 5);
  ASSERT_EQ(obs.points.size(), 5u);
  for (const Eigen::Vector3d& p : obs.points) EXPECT_NEAR(p.z(), chest.z(), 1e-12);
}

TEST(StaticSceneVoxels, EmptyOrNonFiniteInputLearnsNothing) {
  const Scene s;
  StaticSceneVoxels map(s.camera, StaticSceneOptions{});
  PersonBlob empty;  // no grid (a frame without readings)
  map.Learn(empty, s.rays, s.world_from_sensor, s.body, s.posed);
  BodyObservation obs;
  EXPECT_EQ(map.DropStatic(s.world_from_sensor, std::nullopt, &obs), 0);
  obs.points.push_back(s.world_from_sensor.inverse() * s.BoxCentre());
  EXPECT_EQ(map.DropStatic(s.world_from_sensor, std::nullopt, &obs), 0);
  // A pose that is not finite teaches nothing and drops nothing.
  Eigen::Isometry3d nan_pose = s.world_from_sensor;
  nan_pose.translation().x() = std::numeric_limits<double>::quiet_NaN();
  for (int f = 0; f < 12; ++f) map.Learn(s.Blob(), s.rays, nan_pose, s.body, s.posed);
  EXPECT_FALSE(map.IsStatic(s.BoxCentre()));
  // Cleared, a learned scene is gone.
  for (int f = 0; f < 12; ++f) map.Learn(s.Blob(), s.rays, s.world_from_sensor, s.body, s.posed);
  obs.points.assign(1, s.world_from_sensor.inverse() * s.BoxCentre());
  EXPECT_EQ(map.DropStatic(nan_pose, std::nullopt, &obs), 0);
  ASSERT_TRUE(map.IsStatic(s.BoxCentre()));
  map.Clear();
  EXPECT_FALSE(map.IsStatic(s.BoxCentre()));
}

TEST(StaticSceneVoxels, BadOptionsAreABug) {
  const auto bad = [](auto change) {
    StaticSceneOptions o;
    change(o);
    return o;
  };
  EXPECT_THROW(bad([](auto& o) { o.voxel_m = 0; }).Check(), CheckError);
  EXPECT_THROW(bad([](auto& o) { o.min_frames = 0; }).Check(), CheckError);
  EXPECT_THROW(bad([](auto& o) { o.min_frames = 256; }).Check(), CheckError);
  EXPECT_THROW(bad([](auto& o) { o.body_clearance_m = -0.1; }).Check(), CheckError);
  EXPECT_THROW(bad([](auto& o) { o.see_through_m = 0; }).Check(), CheckError);
  EXPECT_THROW(bad([](auto& o) { o.see_through_margin_m = 0; }).Check(), CheckError);
  EXPECT_THROW(bad([](auto& o) { o.floor_clearance_m = -0.01; }).Check(), CheckError);
  EXPECT_THROW(bad([](auto& o) { o.learn_step = 0; }).Check(), CheckError);
  EXPECT_THROW(bad([](auto& o) { o.max_blocks = 0; }).Check(), CheckError);
  EXPECT_THROW(StaticSceneVoxels(PinholeCamera::KinectLike(), bad([](auto& o) { o.voxel_m = -1; })),
               CheckError);
  EXPECT_NO_THROW(StaticSceneOptions{}.Check());
  // Rays of another camera than the map's.
  const Scene s;
  StaticSceneVoxels map(s.camera, StaticSceneOptions{});
  const PixelRays other(PinholeCamera::KinectLike().Cropped(0, 0, 320, 240));
  EXPECT_THROW(map.Learn(s.Blob(), other, s.world_from_sensor, s.body, s.posed), CheckError);
}

}  // namespace
}  // namespace reenact::capture
