// Kinect v1 20-joint text tracks (UTKinect, MSR Action3D, MSR DailyActivity3D, UTD-MHAD):
// files written from a synthetic subject through the inverse mapping
// (skeleton_track_test_util.h) read back to the subject's 16 joints in the sensor frame; one
// test per bad input; UTD-MHAD's real files (../shared/data/utd-mhad) against its README.
#include <gtest/gtest.h>

#include <algorithm>

#include "capture-client/skeleton/kinect_v1_skeleton.h"
#include "tests/unit/capture-client/skeleton_track_test_util.h"

namespace reenact::capture {
namespace {

using namespace skeleton_test;

constexpr double kTol = 1e-8;  // the files carry 9 decimals

void ExpectSkeletonNear(const Skeleton& expected, const Skeleton& actual) {
  for (int j = 0; j < kJointCount; ++j) {
    SCOPED_TRACE(std::string(JointName(static_cast<Joint>(j))));
    EXPECT_EQ(actual.confidence[j], 1.0);
    EXPECT_LT((actual.position[j] - expected.position[j]).norm(), kTol);
  }
}

Expected<SkeletonTrack> Parse(const std::string& text,
                              KinectTextVariant variant = KinectTextVariant::kDetect) {
  KinectV1ReadOptions options;
  options.variant = variant;
  return ParseKinectV1SkeletonText(text, "test.txt", options);
}

std::string UtKinectText(const std::vector<int64_t>& frame_numbers) {
  std::string text;
  for (size_t i = 0; i < frame_numbers.size(); ++i)
    text += UtKinectLine(frame_numbers[i], KinectJoints(SyntheticSkeletonInSensor(0.1 * i)));
  return text;
}

void ExpectError(const Expected<SkeletonTrack>& track, const std::string& code,
                 const std::string& fragment) {
  ASSERT_FALSE(track.ok());
  EXPECT_EQ(track.error().code, code) << track.error().message;
  EXPECT_NE(track.error().message.find(fragment), std::string::npos) << track.error().message;
}

TEST(KinectSkeletonTest, TestSubjectIsSeenFromTheFront) {
  // Guards the construction itself: the subject faces the sensor, so its left shoulder is on
  // the sensor's right (Kinect x, to the sensor's left, smaller) and its head above its waist.
  const auto k = KinectJoints(SyntheticSkeletonInSensor(0));
  EXPECT_LT(k.at("ShoulderLeft").x(), k.at("ShoulderRight").x());
  EXPECT_GT(k.at("Head").y(), k.at("HipCenter").y() + 0.5);
  EXPECT_GT(k.at("HipCenter").z(), 2.0);
}

TEST(KinectSkeletonTest, UtKinectReadsBackTheSubjectInTheSensorFrame) {
  Expected<SkeletonTrack> track = Parse(UtKinectText({190, 191, 195}));
  ASSERT_TRUE(track.ok()) << track.error().message;
  ASSERT_EQ(track->size(), 3u);
  EXPECT_FALSE(track->keyed_by_timestamp());
  EXPECT_NE(track->description().find("UTKinect"), std::string::npos);
  const std::vector<int64_t> numbers = {190, 191, 195};
  for (size_t i = 0; i < 3; ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(track->frames()[i].frame_index, numbers[i]);
    EXPECT_FALSE(track->frames()[i].timestamp_s.has_value());
    ExpectSkeletonNear(SyntheticSkeletonInSensor(0.1 * i), track->frames()[i].skeleton_in_sensor);
  }
  // The sensor frame is OpenCV's: the head is above (smaller y than) the waist, and the
  // subject's left hand is on the sensor's right (larger x) when facing the sensor.
  const Skeleton& s = track->frames()[0].skeleton_in_sensor;
  EXPECT_LT(s[Joint::kHead].y(), s[Joint::kWaist].y());
  EXPECT_GT(s[Joint::kLeftShoulder].x(), s[Joint::kRightShoulder].x());
}

TEST(KinectSkeletonTest, UtKinectFrameNumbersKeyTheLookup) {
  Expected<SkeletonTrack> track = Parse(UtKinectText({190, 191, 195}));
  ASSERT_TRUE(track.ok());
  SkeletonTrackLookupOptions lookup;
  lookup.frame_index_offset = 190;
  track->set_lookup_options(lookup);
  ASSERT_TRUE(track->ForFrame(5, 123.0).has_value());
  EXPECT_LT(((*track->ForFrame(5, 0))[Joint::kHead] - SyntheticSkeletonInSensor(0.2)[Joint::kHead])
                .norm(),
            kTol);
  EXPECT_FALSE(track->ForFrame(2, 0).has_value());   // image 192 has no skeleton
  EXPECT_FALSE(track->ForFrame(-1, 0).has_value());  // before the track
  EXPECT_FALSE(track->ForFrame(6, 0).has_value());   // after it
}

TEST(KinectSkeletonTest, HandFallsBackToWristAndFootToFootWhenUntracked) {
  const Skeleton truth = SyntheticSkeletonInSensor(0.3);
  auto joints = KinectJoints(truth);
  const Eigen::Vector3d wrist = joints.at("WristLeft");
  const Eigen::Vector3d foot = joints.at("FootRight");
  joints["HandLeft"].setZero();
  joints["AnkleRight"].setZero();
  joints["Head"].setZero();
  Expected<SkeletonTrack> track = Parse(UtKinectLine(7, joints));
  ASSERT_TRUE(track.ok()) << track.error().message;
  const Skeleton& s = track->frames()[0].skeleton_in_sensor;
  EXPECT_LT((s[Joint::kLeftHand] - KinectFromSensor(wrist)).norm(), kTol);  // (-x,-y,z) twice
  EXPECT_LT((s[Joint::kRightFoot] - KinectFromSensor(foot)).norm(), kTol);
  EXPECT_FALSE(s.Has(Joint::kHead));
  EXPECT_EQ(s.confidence[Index(Joint::kHead)], 0.0);
  EXPECT_TRUE(s.position[Index(Joint::kHead)].allFinite());
  EXPECT_LT((s[Joint::kRightHand] - truth[Joint::kRightHand]).norm(), kTol);
}

TEST(KinectSkeletonTest, AllZeroFramesHaveNoSkeletonAndRepeatedFrameNumbersAreSkipped) {
  std::map<std::string, Eigen::Vector3d> zeros;
  for (const std::string& name : KinectSdkNames()) zeros[name] = Eigen::Vector3d::Zero();
  const auto first = KinectJoints(SyntheticSkeletonInSensor(0));
  const auto other = KinectJoints(SyntheticSkeletonInSensor(1));
  const std::string text = UtKinectLine(10, first) + UtKinectLine(10, other) +
                           UtKinectLine(11, zeros) + UtKinectLine(12, other);
  Expected<SkeletonTrack> track = Parse(text);
  ASSERT_TRUE(track.ok()) << track.error().message;
  ASSERT_EQ(track->size(), 2u);
  EXPECT_EQ(track->frames()[0].frame_index, 10);
  EXPECT_EQ(track->frames()[1].frame_index, 12);
  ExpectSkeletonNear(SyntheticSkeletonInSensor(0), track->frames()[0].skeleton_in_sensor);
  EXPECT_NE(track->description().find("1 repeated frame number skipped"), std::string::npos)
      << track->description();
}

TEST(KinectSkeletonTest, MsrAction3dReadsBackInItsJointOrder) {
  std::string text;
  for (int f = 0; f < 3; ++f) text += MsrAction3dFrame(KinectJoints(SyntheticSkeletonInSensor(f)));
  Expected<SkeletonTrack> track = Parse(text);
  ASSERT_TRUE(track.ok()) << track.error().message;
  ASSERT_EQ(track->size(), 3u);
  EXPECT_NE(track->description().find("MSR Action3D"), std::string::npos);
  for (int f = 0; f < 3; ++f) {
    SCOPED_TRACE(f);
    EXPECT_EQ(track->frames()[f].frame_index, f);
    ExpectSkeletonNear(SyntheticSkeletonInSensor(f), track->frames()[f].skeleton_in_sensor);
  }
}

TEST(KinectSkeletonTest, MsrDailyActivityUsesTheRealWorldRowsOfTheFirstSkeleton) {
  const auto screen_row = [](const Eigen::Vector3d&) { return std::string("0.5 0.4 2000 0\n"); };
  const auto frame = [&](const std::map<std::string, Eigen::Vector3d>& joints) {
    std::string rows;
    for (const std::string& name : KinectSdkNames())
      rows += Xyz(joints.at(name)) + " 1\n" + screen_row(joints.at(name));
    return rows;
  };
  const auto a = KinectJoints(SyntheticSkeletonInSensor(0));
  const auto b = KinectJoints(SyntheticSkeletonInSensor(1));
  const std::string text = "3 20\n40\n" + frame(a) + "0\n80\n" + frame(b) + frame(a);
  Expected<SkeletonTrack> track = Parse(text);
  ASSERT_TRUE(track.ok()) << track.error().message;
  ASSERT_EQ(track->size(), 2u);
  EXPECT_EQ(track->frames()[0].frame_index, 0);
  EXPECT_EQ(track->frames()[1].frame_index, 2);  // frame 1 has no skeleton
  ExpectSkeletonNear(SyntheticSkeletonInSensor(0), track->frames()[0].skeleton_in_sensor);
  ExpectSkeletonNear(SyntheticSkeletonInSensor(1), track->frames()[1].skeleton_in_sensor);
}

TEST(KinectSkeletonTest, UtdMhadReadsBackInItsJointOrder) {
  std::string text;
  for (int f = 0; f < 3; ++f) text += UtdMhadFrame(KinectJoints(SyntheticSkeletonInSensor(f)));
  Expected<SkeletonTrack> track = Parse(text);
  ASSERT_TRUE(track.ok()) << track.error().message;
  ASSERT_EQ(track->size(), 3u);
  EXPECT_NE(track->description().find("UTD-MHAD"), std::string::npos);
  for (int f = 0; f < 3; ++f) {
    SCOPED_TRACE(f);
    EXPECT_EQ(track->frames()[f].frame_index, f);
    ExpectSkeletonNear(SyntheticSkeletonInSensor(f), track->frames()[f].skeleton_in_sensor);
  }
}

TEST(KinectSkeletonTest, UtdMhadAllZeroFrameHasNoSkeleton) {
  std::map<std::string, Eigen::Vector3d> zeros;
  for (const std::string& name : KinectSdkNames()) zeros[name] = Eigen::Vector3d::Zero();
  const std::string text = UtdMhadFrame(KinectJoints(SyntheticSkeletonInSensor(0))) +
                           UtdMhadFrame(zeros) +
                           UtdMhadFrame(KinectJoints(SyntheticSkeletonInSensor(2)));
  Expected<SkeletonTrack> track = Parse(text, KinectTextVariant::kUtdMhad);
  ASSERT_TRUE(track.ok()) << track.error().message;
  ASSERT_EQ(track->size(), 2u);
  EXPECT_EQ(track->frames()[1].frame_index, 2);
  ExpectSkeletonNear(SyntheticSkeletonInSensor(2), track->frames()[1].skeleton_in_sensor);
}

TEST(KinectSkeletonTest, UtdMhadFileCutOffInsideAFrameIsAnError) {
  std::string text = UtdMhadFrame(KinectJoints(SyntheticSkeletonInSensor(0)));
  const std::string second = UtdMhadFrame(KinectJoints(SyntheticSkeletonInSensor(1)));
  size_t at = 0;
  for (int k = 0; k < 7; ++k) at = second.find('\n', at) + 1;
  text += second.substr(0, at);  // 27 joint lines
  ExpectError(Parse(text), "corrupt", "line 27: the file ends inside a frame: 27 joint lines");
}

TEST(KinectSkeletonTest, UtdMhadShortLineIsAnError) {
  std::string text = UtdMhadFrame(KinectJoints(SyntheticSkeletonInSensor(0)));
  text.insert(text.find('\n', text.find('\n') + 1) + 1, "0.1 2.5\n");  // a new line 3
  ExpectError(Parse(text), "corrupt", "line 3: has 2 numbers, expected 3");
}

TEST(KinectSkeletonTest, UtdMhadNonNumberIsAnError) {
  std::string text = UtdMhadFrame(KinectJoints(SyntheticSkeletonInSensor(0)));
  text[text.find('\n') + 1] = 'x';  // line 2 starts with "x"
  ExpectError(Parse(text), "corrupt", "line 2: \"x");
}

TEST(KinectSkeletonTest, UtdMhadMillimetresAreRefused) {
  auto joints = KinectJoints(SyntheticSkeletonInSensor(0));
  for (auto& [name, p] : joints) p *= 1000;
  ExpectError(Parse(UtdMhadFrame(joints)), "unsupported", "not a position in metres");
}

TEST(KinectSkeletonTest, ScreenCoordinatesAreRefused) {
  std::string text;
  for (int j = 0; j < 20; ++j) text += std::to_string(120 + j) + " 80 2150 0\n";
  ExpectError(Parse(text), "unsupported", "skeleton3D.txt");
}

TEST(KinectSkeletonTest, MillimetresAreRefused) {
  auto joints = KinectJoints(SyntheticSkeletonInSensor(0));
  for (auto& [name, p] : joints) p *= 1000;
  ExpectError(Parse(UtKinectLine(1, joints)), "unsupported", "not a position in metres");
}

TEST(KinectSkeletonTest, EmptyFileIsAnError) {
  ExpectError(Parse(""), "corrupt", "empty");
  ExpectError(Parse(" \n\r\n\t\n"), "corrupt", "empty");
}

TEST(KinectSkeletonTest, TruncatedUtKinectLineIsAnError) {
  std::string text = UtKinectText({1, 2});
  text = text.substr(0, text.size() - 40) + "\n";  // cut the last line short
  ExpectError(Parse(text), "corrupt", "line 2: has 5");
}

TEST(KinectSkeletonTest, WrongJointCountIsAnError) {
  ExpectError(Parse("3 15\n0\n0\n0\n"), "corrupt", "Kinect v1 files have 20");
  std::string msr = MsrAction3dFrame(KinectJoints(SyntheticSkeletonInSensor(0)));
  msr += "0.1 0.2 2.0 0\n";  // 21 joint lines
  ExpectError(Parse(msr), "corrupt", "not a multiple of 20");
}

TEST(KinectSkeletonTest, TruncatedDailyActivityFileIsAnError) {
  ExpectError(Parse("2 20\n0\n"), "corrupt", "ends after 1 of the 2 frames");
}

TEST(KinectSkeletonTest, UnknownLayoutIsAnError) {
  ExpectError(Parse("1 2 3 4 5 6 7\n"), "corrupt", "has 7 numbers");
}

TEST(KinectSkeletonTest, NanIsAnError) {
  std::string text = UtKinectText({1});
  text.insert(text.find(' ') + 1, "nan ");
  text.erase(text.rfind(' '));
  ExpectError(Parse(text + "\n"), "corrupt", "\"nan\" is not a finite number");
}

TEST(KinectSkeletonTest, NonNumberIsAnError) {
  std::string text = UtKinectText({1});
  text[0] = 'x';
  ExpectError(Parse(text), "corrupt", "\"x\" is not a number");
}

TEST(KinectSkeletonTest, NonIntegralFrameNumberIsAnError) {
  std::string text = UtKinectText({1});
  text.insert(1, ".5");
  ExpectError(Parse(text), "corrupt", "frame number 1.5");
}

TEST(KinectSkeletonTest, BackwardFrameNumberIsAnError) {
  ExpectError(Parse(UtKinectText({5, 4})), "corrupt", "line 2: frame number 4 comes after");
}

TEST(KinectSkeletonTest, ForcedVariantChecksTheLayout) {
  ExpectError(Parse(UtKinectText({1}), KinectTextVariant::kMsrAction3d), "corrupt", "expected 4");
  const std::string msr = MsrAction3dFrame(KinectJoints(SyntheticSkeletonInSensor(0)));
  ExpectError(Parse(msr, KinectTextVariant::kUtdMhad), "corrupt",
              "line 1: has 4 numbers, expected 3");
}

TEST(KinectSkeletonTest, MissingFileIsNotFound) {
  TempDir dir;
  Expected<SkeletonTrack> track = ReadKinectV1SkeletonTrack((dir.path() / "no.txt").string());
  ExpectError(track, "not_found", "no.txt");
}

TEST(KinectSkeletonTest, ReadsAFile) {
  TempDir dir;
  const fs::path file = dir.path() / "joints_s01_e01.txt";
  WriteText(file, UtKinectText({3, 4}));
  Expected<SkeletonTrack> track = ReadKinectV1SkeletonTrack(file.string());
  ASSERT_TRUE(track.ok()) << track.error().message;
  EXPECT_EQ(track->size(), 2u);
  EXPECT_NE(track->description().find("joints_s01_e01.txt"), std::string::npos);
}

TEST(KinectSkeletonTest, VariantNamesRoundTrip) {
  for (KinectTextVariant v :
       {KinectTextVariant::kDetect, KinectTextVariant::kUtKinect, KinectTextVariant::kMsrAction3d,
        KinectTextVariant::kMsrDailyActivity3d, KinectTextVariant::kUtdMhad})
    EXPECT_EQ(KinectTextVariantFromName(KinectTextVariantName(v)), v);
  EXPECT_EQ(KinectTextVariantName(KinectTextVariant::kUtdMhad), "utd-mhad");
  EXPECT_FALSE(KinectTextVariantFromName("kinect2").has_value());
}

// UTD-MHAD's skeleton.txt of a sequence (../shared/data/utd-mhad, README there).
std::string UtdMhadSkeletonFile(const std::string& sequence) {
  return (fs::path(REENACT_SHARED_DATA_DIR) / "utd-mhad" / sequence / "skeleton.txt").string();
}

TEST(KinectSkeletonTest, UtdMhadRealFileHasItsFramesWithTheHeadUp) {
  // a1_s1_t1: 960 lines = 48 frames (its camera.json says 48), a person standing.
  Expected<SkeletonTrack> track = ReadKinectV1SkeletonTrack(UtdMhadSkeletonFile("a1_s1_t1"));
  ASSERT_TRUE(track.ok()) << track.error().message;
  ASSERT_EQ(track->size(), 48u);
  EXPECT_NE(track->description().find("UTD-MHAD"), std::string::npos);
  for (size_t f = 0; f < track->size(); ++f) {
    SCOPED_TRACE(f);
    const Skeleton& s = track->frames()[f].skeleton_in_sensor;
    EXPECT_EQ(track->frames()[f].frame_index, static_cast<int64_t>(f));
    for (int j = 0; j < kJointCount; ++j) EXPECT_EQ(s.confidence[j], 1.0);
    // OpenCV sensor frame: y down, so the head has the smaller y; a standing adult's head is
    // well over 0.4 m above the pelvis; 2.5-3 m away.
    EXPECT_LT(s[Joint::kHead].y(), s[Joint::kWaist].y() - 0.4);
    EXPECT_GT(s[Joint::kWaist].z(), 2.0);
    EXPECT_LT(s[Joint::kWaist].z(), 3.5);
  }
}

TEST(KinectSkeletonTest, UtdMhadRightHandWaveMovesTheRightHandOnTheSensorsLeft) {
  // a3 is the right hand wave; the README places the moving hand (right_hand) at Kinect
  // x = +0.22 m, i.e. sensor x = -0.22 m: a person facing a true camera has the right hand
  // on the image's left.
  KinectV1ReadOptions options;
  options.variant = KinectTextVariant::kUtdMhad;
  Expected<SkeletonTrack> track =
      ReadKinectV1SkeletonTrack(UtdMhadSkeletonFile("a3_s1_t1"), options);
  ASSERT_TRUE(track.ok()) << track.error().message;
  ASSERT_GT(track->size(), 10u);
  const Skeleton& first = track->frames()[0].skeleton_in_sensor;
  std::array<double, kJointCount> travel{};
  double right_hand_x = 0, left_hand_x = 0;
  for (const SkeletonTrackFrame& frame : track->frames()) {
    const Skeleton& s = frame.skeleton_in_sensor;
    for (int j = 0; j < kJointCount; ++j)
      travel[j] = std::max(travel[j], (s.position[j] - first.position[j]).norm());
    right_hand_x += s[Joint::kRightHand].x() / track->size();
    left_hand_x += s[Joint::kLeftHand].x() / track->size();
  }
  const auto most = std::max_element(travel.begin(), travel.end()) - travel.begin();
  EXPECT_EQ(static_cast<Joint>(most), Joint::kRightHand) << JointName(static_cast<Joint>(most));
  EXPECT_GT(travel[Index(Joint::kRightHand)], 0.5);  // a wave, not jitter
  EXPECT_NEAR(right_hand_x, -0.22, 0.05);
  EXPECT_GT(left_hand_x, 0.1);
}

}  // namespace
}  // namespace reenact::capture
