// LoadSkeletonTrack: the command-line forms json:FILE, kinect:FILE and FILE.json, their
// options, and the errors for unknown forms and options.
#include "capture-client/skeleton/skeleton_track_spec.h"

#include <gtest/gtest.h>

#include "capture-client/skeleton/skeleton_track_json.h"
#include "tests/unit/capture-client/skeleton_track_test_util.h"

namespace reenact::capture {
namespace {

using namespace skeleton_test;

class SkeletonTrackSpecTest : public ::testing::Test {
 protected:
  void SetUp() override {
    kinect_ = (dir_.path() / "joints_s01_e01.txt").string();
    WriteText(kinect_, UtKinectLine(190, KinectJoints(SyntheticSkeletonInSensor(0))) +
                           UtKinectLine(191, KinectJoints(SyntheticSkeletonInSensor(1))));
    json_ = (dir_.path() / "take.json").string();
    SkeletonTrackFrame a, b;
    a.timestamp_s = 5.0;
    a.skeleton_in_sensor = SyntheticSkeletonInSensor(0);
    b.timestamp_s = 5.5;
    b.skeleton_in_sensor = SyntheticSkeletonInSensor(1);
    ASSERT_TRUE(WriteSkeletonTrackJson(SkeletonTrack::Create({a, b}, "take").value(), json_).ok());
  }

  TempDir dir_;
  std::string kinect_, json_;
};

void ExpectUsage(const Expected<SkeletonTrack>& track, const std::string& fragment) {
  ASSERT_FALSE(track.ok());
  EXPECT_EQ(track.error().code, "usage") << track.error().message;
  EXPECT_NE(track.error().message.find(fragment), std::string::npos) << track.error().message;
}

TEST_F(SkeletonTrackSpecTest, KinectFormDetectsTheLayoutAndTakesTheFrameOffset) {
  Expected<SkeletonTrack> track = LoadSkeletonTrack("kinect:" + kinect_ + "?frame_offset=190");
  ASSERT_TRUE(track.ok()) << track.error().message;
  EXPECT_EQ(track->size(), 2u);
  EXPECT_EQ(track->lookup_options().frame_index_offset, 190);
  const std::optional<Skeleton> s = track->ForFrame(1, 0);
  ASSERT_TRUE(s.has_value());
  EXPECT_LT(((*s)[Joint::kLeftHand] - SyntheticSkeletonInSensor(1)[Joint::kLeftHand]).norm(), 1e-8);
  EXPECT_FALSE(track->ForFrame(2, 0).has_value());
}

TEST_F(SkeletonTrackSpecTest, KinectVariantOptionForcesTheLayout) {
  ASSERT_TRUE(LoadSkeletonTrack("kinect:" + kinect_ + "?variant=utkinect").ok());
  Expected<SkeletonTrack> wrong = LoadSkeletonTrack("kinect:" + kinect_ + "?variant=msr-action3d");
  ASSERT_FALSE(wrong.ok());
  EXPECT_EQ(wrong.error().code, "corrupt");
  ExpectUsage(LoadSkeletonTrack("kinect:" + kinect_ + "?variant=kinect2"), "variant=kinect2");
}

TEST_F(SkeletonTrackSpecTest, KinectFormReadsUtdMhad) {
  const std::string file = (dir_.path() / "skeleton.txt").string();
  WriteText(file, UtdMhadFrame(KinectJoints(SyntheticSkeletonInSensor(0))) +
                      UtdMhadFrame(KinectJoints(SyntheticSkeletonInSensor(1))));
  for (const char* option : {"", "?variant=utd-mhad"}) {
    SCOPED_TRACE(option);
    Expected<SkeletonTrack> track = LoadSkeletonTrack("kinect:" + file + option);
    ASSERT_TRUE(track.ok()) << track.error().message;
    ASSERT_EQ(track->size(), 2u);
    const std::optional<Skeleton> s = track->ForFrame(1, 0);
    ASSERT_TRUE(s.has_value());
    EXPECT_LT(((*s)[Joint::kHead] - SyntheticSkeletonInSensor(1)[Joint::kHead]).norm(), 1e-8);
  }
  EXPECT_FALSE(LoadSkeletonTrack("kinect:" + kinect_ + "?variant=utd-mhad").ok());
}

TEST_F(SkeletonTrackSpecTest, JsonFormsReadOurFormatWithTheirOptions) {
  Expected<SkeletonTrack> plain = LoadSkeletonTrack(json_);
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  EXPECT_TRUE(plain->keyed_by_timestamp());
  EXPECT_TRUE(plain->ForFrame(0, 5.01).has_value());
  Expected<SkeletonTrack> shifted =
      LoadSkeletonTrack("json:" + json_ + "?time_offset_s=5&tolerance_s=0.1");
  ASSERT_TRUE(shifted.ok()) << shifted.error().message;
  EXPECT_TRUE(shifted->ForFrame(0, 0.45).has_value());  // 5.45 is within 0.1 s of 5.5
  EXPECT_FALSE(shifted->ForFrame(0, 0.3).has_value());
}

TEST_F(SkeletonTrackSpecTest, UnknownFormListsTheAcceptedOnes) {
  ExpectUsage(LoadSkeletonTrack("bvh:" + kinect_), "json:FILE, kinect:FILE");
  ExpectUsage(LoadSkeletonTrack(kinect_), "unknown skeleton source");  // .txt without kinect:
}

TEST_F(SkeletonTrackSpecTest, BadOptionsAreUsageErrors) {
  ExpectUsage(LoadSkeletonTrack("json:" + json_ + "?speed=2"), "unknown option 'speed'");
  ExpectUsage(LoadSkeletonTrack("kinect:" + kinect_ + "?frame_offset=1.5"), "frame_offset=1.5");
  ExpectUsage(LoadSkeletonTrack("json:" + json_ + "?tolerance_s=-1"), "tolerance_s=-1");
  ExpectUsage(LoadSkeletonTrack("json:" + json_ + "?time_offset_s=nan"), "time_offset_s=nan");
  ExpectUsage(LoadSkeletonTrack("kinect:"), "needs a file");
}

TEST_F(SkeletonTrackSpecTest, MissingFileIsNotFound) {
  Expected<SkeletonTrack> track = LoadSkeletonTrack("kinect:" + kinect_ + ".gone");
  ASSERT_FALSE(track.ok());
  EXPECT_EQ(track.error().code, "not_found");
  track = LoadSkeletonTrack((dir_.path() / "gone.json").string());
  ASSERT_FALSE(track.ok());
  EXPECT_EQ(track.error().code, "not_found");
}

}  // namespace
}  // namespace reenact::capture
