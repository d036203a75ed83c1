// SkeletonTrack: frame lookup by timestamp (nearest within the tolerance) and by frame index
// (with the offset), and the validation of constructed tracks.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "capture-client/skeleton/skeleton_track.h"

namespace reenact::capture {
namespace {

// A skeleton whose head x carries `tag`, so a lookup result names its frame.
Skeleton Tagged(double tag) {
  Skeleton s;
  s.Set(Joint::kHead, Eigen::Vector3d(tag, -0.5, 2.5), 0.9);
  return s;
}

double TagOf(const std::optional<Skeleton>& s) { return s ? (*s)[Joint::kHead].x() : -1; }

SkeletonTrackFrame Timed(double t, double tag) {
  SkeletonTrackFrame f;
  f.timestamp_s = t;
  f.skeleton_in_sensor = Tagged(tag);
  return f;
}

SkeletonTrackFrame Indexed(int64_t index, double tag) {
  SkeletonTrackFrame f;
  f.frame_index = index;
  f.skeleton_in_sensor = Tagged(tag);
  return f;
}

void ExpectCorrupt(const Expected<SkeletonTrack>& track, const std::string& fragment) {
  ASSERT_FALSE(track.ok());
  EXPECT_EQ(track.error().code, "corrupt");
  EXPECT_NE(track.error().message.find(fragment), std::string::npos) << track.error().message;
}

TEST(SkeletonTrackLookupTest, ByTimestampTakesTheNearestFrameWithinTheTolerance) {
  // Frames at 30 Hz from t = 10 s, one missing (10.1).
  Expected<SkeletonTrack> track = SkeletonTrack::Create(
      {Timed(10.0, 0), Timed(10.0 + 1 / 30.0, 1), Timed(10.0 + 2 / 30.0, 2), Timed(10.2, 6)},
      "timed");
  ASSERT_TRUE(track.ok()) << track.error().message;
  EXPECT_TRUE(track->keyed_by_timestamp());
  EXPECT_EQ(track->size(), 4u);
  EXPECT_EQ(TagOf(track->ForFrame(999, 10.0)), 0);      // exact; the index is ignored
  EXPECT_EQ(TagOf(track->ForFrame(0, 10.04)), 1);       // 6.7 ms from frame 1
  EXPECT_EQ(TagOf(track->ForFrame(0, 10.06)), 2);       // 6.7 ms from frame 2
  EXPECT_EQ(TagOf(track->ForFrame(0, 10.19)), 6);       // 10 ms before 10.2
  EXPECT_EQ(TagOf(track->ForFrame(0, 9.99)), 0);        // before the first, within 1/60 s
  EXPECT_FALSE(track->ForFrame(0, 9.98).has_value());   // 20 ms before the first
  EXPECT_FALSE(track->ForFrame(0, 10.1).has_value());   // in the gap: 33 ms from both
  EXPECT_FALSE(track->ForFrame(0, 10.22).has_value());  // after the last
  EXPECT_FALSE(track->ForFrame(0, std::numeric_limits<double>::quiet_NaN()).has_value());
  EXPECT_FALSE(track->ForFrame(0, std::numeric_limits<double>::infinity()).has_value());
  // The returned skeleton is the stored one, confidence included.
  EXPECT_EQ(track->ForFrame(0, 10.0)->confidence[Index(Joint::kHead)], 0.9);
  EXPECT_FALSE(track->ForFrame(0, 10.0)->Has(Joint::kNeck));
}

TEST(SkeletonTrackLookupTest, EquallyNearFramesGiveTheEarlierOne) {
  Expected<SkeletonTrack> track = SkeletonTrack::Create({Timed(1.0, 1), Timed(2.0, 2)}, "tie");
  ASSERT_TRUE(track.ok());
  SkeletonTrackLookupOptions options;
  options.timestamp_tolerance_s = 0.5;
  track->set_lookup_options(options);
  EXPECT_EQ(TagOf(track->ForFrame(0, 1.5)), 1);
  EXPECT_EQ(TagOf(track->ForFrame(0, 1.5000001)), 2);
}

TEST(SkeletonTrackLookupTest, TimestampOffsetAndToleranceApply) {
  SkeletonTrackLookupOptions options;
  options.timestamp_offset_s = 100;  // track clock = capture clock + 100 s
  options.timestamp_tolerance_s = 0.001;
  Expected<SkeletonTrack> track =
      SkeletonTrack::Create({Timed(100.0, 1), Timed(100.5, 2)}, "offset", options);
  ASSERT_TRUE(track.ok());
  EXPECT_EQ(TagOf(track->ForFrame(0, 0.5)), 2);
  EXPECT_EQ(TagOf(track->ForFrame(0, 0.0009)), 1);
  EXPECT_FALSE(track->ForFrame(0, 0.002).has_value());
  EXPECT_FALSE(track->ForFrame(0, 100.0).has_value());
}

TEST(SkeletonTrackLookupTest, ByIndexMatchesExactlyWithTheOffset) {
  SkeletonTrackLookupOptions options;
  options.frame_index_offset = 190;  // capture frame 0 = image 190
  Expected<SkeletonTrack> track = SkeletonTrack::Create(
      {Indexed(190, 0), Indexed(191, 1), Indexed(195, 5)}, "indexed", options);
  ASSERT_TRUE(track.ok());
  EXPECT_FALSE(track->keyed_by_timestamp());
  EXPECT_EQ(TagOf(track->ForFrame(0, 1e9)), 0);  // the timestamp is ignored
  EXPECT_EQ(TagOf(track->ForFrame(1, 0)), 1);
  EXPECT_EQ(TagOf(track->ForFrame(5, 0)), 5);
  EXPECT_FALSE(track->ForFrame(2, 0).has_value());                                    // a gap
  EXPECT_FALSE(track->ForFrame(-1, 0).has_value());                                   // before
  EXPECT_FALSE(track->ForFrame(6, 0).has_value());                                    // after
  EXPECT_FALSE(track->ForFrame(std::numeric_limits<int64_t>::max(), 0).has_value());  // overflow
}

TEST(SkeletonTrackLookupTest, EmptyTrackIsAnError) {
  ExpectCorrupt(SkeletonTrack::Create({}, "empty"), "no frames");
}

TEST(SkeletonTrackLookupTest, MixedTimestampsAreAnError) {
  ExpectCorrupt(SkeletonTrack::Create({Timed(1, 0), Indexed(2, 0)}, "mixed"),
                "frame 1: has no timestamp_s");
}

TEST(SkeletonTrackLookupTest, FrameWithoutKeyIsAnError) {
  ExpectCorrupt(SkeletonTrack::Create({SkeletonTrackFrame{}}, "keyless"),
                "neither timestamp_s nor frame_index");
}

TEST(SkeletonTrackLookupTest, DuplicateTimestampIsAnError) {
  ExpectCorrupt(SkeletonTrack::Create({Timed(1, 0), Timed(1, 1)}, "dup"),
                "frame 1: timestamp_s 1 is not after");
}

TEST(SkeletonTrackLookupTest, DecreasingFrameIndexIsAnError) {
  ExpectCorrupt(SkeletonTrack::Create({Indexed(3, 0), Indexed(2, 1)}, "down"),
                "frame 1: frame_index 2 is not after");
}

TEST(SkeletonTrackLookupTest, BadJointValuesAreErrors) {
  SkeletonTrackFrame f = Indexed(0, 0);
  f.skeleton_in_sensor.confidence[Index(Joint::kNeck)] = 2;
  ExpectCorrupt(SkeletonTrack::Create({f}, "conf"), "joint neck: confidence 2");
  f = Indexed(0, 0);
  f.skeleton_in_sensor.position[Index(Joint::kTorso)].y() = std::nan("");
  ExpectCorrupt(SkeletonTrack::Create({f}, "nan"), "joint torso: position is not finite");
}

TEST(SkeletonTrackLookupTest, BadOptionsAreRefused) {
  SkeletonTrackLookupOptions options;
  options.timestamp_tolerance_s = -1;
  EXPECT_THROW(options.Check(), CheckError);
  options.timestamp_tolerance_s = std::nan("");
  EXPECT_THROW(options.Check(), CheckError);
}

}  // namespace
}  // namespace reenact::capture
