#include "capture-client/slam/slam_map.h"

#include <gtest/gtest.h>

#include <cstring>

#include "common/error/check.h"
#include "proto/clip/map_codec.h"

namespace reenact::capture::slam {
namespace {

// A keyframe with n keypoints whose descriptors are all-zero except byte 0 = the index and
// byte 1 = `tag`.
Keyframe MakeKeyframe(int n, uint8_t tag, const Eigen::Vector3d& centre = Eigen::Vector3d::Zero()) {
  Keyframe kf;
  kf.sensor_from_world = Eigen::Isometry3d::Identity();
  kf.sensor_from_world.translation() = -centre;
  kf.observations.resize(n);
  kf.descriptors = cv::Mat::zeros(n, 32, CV_8UC1);
  for (int i = 0; i < n; ++i) {
    kf.descriptors.at<uint8_t>(i, 0) = static_cast<uint8_t>(i);
    kf.descriptors.at<uint8_t>(i, 1) = tag;
  }
  return kf;
}

TEST(SlamMap, PointsKeepTheirObservationsBothWays) {
  SlamMap map;
  const int a = map.AddKeyframe(MakeKeyframe(5, 0));
  const int b = map.AddKeyframe(MakeKeyframe(5, 0));
  const int p = map.AddPoint({1, 2, 3}, a, 2);
  map.AddObservation(p, b, 4);
  map.AddObservation(p, b, 3);  // second observation in the same keyframe: ignored
  EXPECT_EQ(map.points()[p].observations.size(), 2u);
  EXPECT_EQ(map.keyframes()[a].point_ids[2], p);
  EXPECT_EQ(map.keyframes()[b].point_ids[4], p);
  EXPECT_EQ(map.keyframes()[b].point_ids[3], -1);
  EXPECT_NEAR(map.points()[p].reference_distance_m, std::sqrt(14.0), 1e-12);
  map.RemoveObservation(p, a);
  EXPECT_EQ(map.keyframes()[a].point_ids[2], -1);
  EXPECT_FALSE(map.points()[p].bad);
  map.RemoveObservation(p, b);
  EXPECT_TRUE(map.points()[p].bad);  // nobody sees it any more
  EXPECT_EQ(map.good_point_count(), 0);
}

TEST(SlamMap, CullingDetachesThePointEverywhere) {
  SlamMap map;
  const int a = map.AddKeyframe(MakeKeyframe(3, 0));
  const int b = map.AddKeyframe(MakeKeyframe(3, 0));
  const int p = map.AddPoint({0, 0, 2}, a, 0);
  map.AddObservation(p, b, 1);
  map.CullPoint(p);
  EXPECT_TRUE(map.points()[p].bad);
  EXPECT_EQ(map.keyframes()[a].point_ids[0], -1);
  EXPECT_EQ(map.keyframes()[b].point_ids[1], -1);
  map.AddObservation(p, b, 2);  // a bad point takes no new observations
  EXPECT_EQ(map.keyframes()[b].point_ids[2], -1);
}

TEST(SlamMap, RepresentativeDescriptorIsTheMedoid) {
  SlamMap map;
  // Three keyframes see the point with descriptors that differ in byte 1: 0x00, 0x01, 0xFF.
  // Distances: 00-01 = 1, 00-FF = 8, 01-FF = 7; medians 1, 1, 7: the first of 00 and 01.
  const int a = map.AddKeyframe(MakeKeyframe(1, 0xFF));
  const int b = map.AddKeyframe(MakeKeyframe(1, 0x00));
  const int c = map.AddKeyframe(MakeKeyframe(1, 0x01));
  const int p = map.AddPoint({0, 0, 1}, a, 0);
  EXPECT_EQ(map.points()[p].descriptor[1], 0xFF);
  map.AddObservation(p, b, 0);
  map.AddObservation(p, c, 0);
  map.UpdateDescriptor(p);
  EXPECT_EQ(map.points()[p].descriptor[1], 0x00);
}

TEST(SlamMap, PredictedOctaveFollowsTheDistance) {
  SlamMap map;
  Keyframe kf = MakeKeyframe(1, 0);
  kf.observations[0].octave = 2;
  const int a = map.AddKeyframe(kf);
  const int p = map.AddPoint({0, 0, 2}, a, 0);
  EXPECT_EQ(map.PredictOctave(p, 2.0, 1.2, 8), 2);
  EXPECT_EQ(map.PredictOctave(p, 2.0 / 1.44, 1.2, 8), 4);  // closer: larger in the image
  EXPECT_EQ(map.PredictOctave(p, 2.0 * 1.2, 1.2, 8), 1);
  EXPECT_EQ(map.PredictOctave(p, 100, 1.2, 8), 0);  // clamped
  EXPECT_EQ(map.PredictOctave(p, 0.01, 1.2, 8), 7);
}

TEST(SlamMap, ExportKeepsOnlyWellObservedGoodPointsAndEncodes) {
  SlamMap map;
  std::vector<int> kfs;
  for (int k = 0; k < 4; ++k) kfs.push_back(map.AddKeyframe(MakeKeyframe(4, 0)));
  const int seen_once = map.AddPoint({0, 0, 1}, kfs[0], 0);
  const int seen_thrice = map.AddPoint({1, 0, 1}, kfs[0], 1);
  map.AddObservation(seen_thrice, kfs[1], 1);
  map.AddObservation(seen_thrice, kfs[2], 1);
  const int seldom_found = map.AddPoint({2, 0, 1}, kfs[0], 2);
  for (int k = 1; k < 4; ++k) map.AddObservation(seldom_found, kfs[k], 2);
  map.points()[seldom_found].visible = 10;
  map.points()[seldom_found].found = 2;  // 0.2 < 0.25
  const int culled = map.AddPoint({3, 0, 1}, kfs[0], 3);
  for (int k = 1; k < 4; ++k) map.AddObservation(culled, kfs[k], 3);
  map.CullPoint(culled);
  (void)seen_once;

  const proto::ClipMap exported = map.ExportClipMap();
  ASSERT_EQ(exported.points.size(), 1u);
  EXPECT_EQ(exported.points[0].position_in_world, Eigen::Vector3d(1, 0, 1));
  EXPECT_EQ(exported.points[0].observations, 3u);
  EXPECT_EQ(exported.points[0].descriptor[0], 1);
  MapExportOptions lenient;
  lenient.min_observations = 1;
  lenient.min_found_ratio = 0;
  EXPECT_EQ(map.ExportClipMap(lenient).points.size(), 3u);

  const auto bytes = proto::EncodeMap(exported, proto::MapCodecOptions{});
  ASSERT_TRUE(bytes.ok());
  const auto decoded = proto::DecodeMap(*bytes);
  ASSERT_TRUE(decoded.ok());
  EXPECT_EQ(decoded->points.size(), 1u);
  EXPECT_EQ(decoded->points[0].descriptor, exported.points[0].descriptor);
}

TEST(SlamMap, BadExportOptionsAreBugs) {
  MapExportOptions o;
  o.min_observations = 0;
  EXPECT_THROW(o.Check(), CheckError);
  o = {};
  o.min_found_ratio = 1.5;
  EXPECT_THROW(o.Check(), CheckError);
}

}  // namespace
}  // namespace reenact::capture::slam
