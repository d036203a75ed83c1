// Our JSON skeleton track: a hand-written document reads to the values it states, a written
// track reads back bit-identical, and every malformed document is a clear error naming the
// frame and the field.
#include "capture-client/skeleton/skeleton_track_json.h"

#include <gtest/gtest.h>

#include <cstring>

#include "tests/unit/capture-client/skeleton_track_test_util.h"

namespace reenact::capture {
namespace {

using namespace skeleton_test;

std::string Document(const std::string& frames, const std::string& head = "") {
  return R"({"format": "reenact-skeleton-track", "version": 1, "frame": "sensor", )" + head +
         R"("frames": [)" + frames + "]}";
}

constexpr const char* kHead = R"("head": {"position": [0.02, -0.61, 2.48], "confidence": 1})";

void ExpectCorrupt(const std::string& text, const std::string& fragment) {
  Expected<SkeletonTrack> track = ParseSkeletonTrackJson(text, "t.json");
  ASSERT_FALSE(track.ok());
  EXPECT_EQ(track.error().code, "corrupt") << track.error().message;
  EXPECT_NE(track.error().message.find(fragment), std::string::npos) << track.error().message;
  EXPECT_EQ(track.error().message.rfind("t.json", 0), 0u) << track.error().message;
}

TEST(SkeletonTrackJsonTest, HandWrittenDocumentReadsItsValues) {
  const std::string text =
      Document(std::string(R"({"timestamp_s": 0.5, "frame_index": 15, "joints": {)") + kHead +
                   R"(, "l_hand": {"position": [0.3, 0.1, 2.2], "confidence": 0.25}}},
          {"timestamp_s": 0.5333, "joints": {}})",
               R"("description": "take 3", "extra": [1, 2], )");
  Expected<SkeletonTrack> track = ParseSkeletonTrackJson(text, "t.json");
  ASSERT_TRUE(track.ok()) << track.error().message;
  ASSERT_EQ(track->size(), 2u);
  EXPECT_TRUE(track->keyed_by_timestamp());
  EXPECT_EQ(track->description(), "t.json: take 3");
  const SkeletonTrackFrame& f = track->frames()[0];
  EXPECT_EQ(f.timestamp_s, 0.5);
  EXPECT_EQ(f.frame_index, 15);
  EXPECT_EQ(f.skeleton_in_sensor[Joint::kHead], Eigen::Vector3d(0.02, -0.61, 2.48));
  EXPECT_EQ(f.skeleton_in_sensor.confidence[Index(Joint::kHead)], 1.0);
  EXPECT_EQ(f.skeleton_in_sensor[Joint::kLeftHand], Eigen::Vector3d(0.3, 0.1, 2.2));
  EXPECT_EQ(f.skeleton_in_sensor.confidence[Index(Joint::kLeftHand)], 0.25);
  EXPECT_FALSE(f.skeleton_in_sensor.Has(Joint::kNeck));
  EXPECT_FALSE(track->frames()[1].frame_index.has_value());
  for (int j = 0; j < kJointCount; ++j)
    EXPECT_EQ(track->frames()[1].skeleton_in_sensor.confidence[j], 0);
  EXPECT_EQ((*track->ForFrame(0, 0.51))[Joint::kHead].z(), 2.48);
}

TEST(SkeletonTrackJsonTest, WrittenTrackReadsBackBitIdentical) {
  std::vector<SkeletonTrackFrame> frames;
  for (int i = 0; i < 4; ++i) {
    SkeletonTrackFrame f;
    f.timestamp_s = 0.1 * i + 1.0 / 3.0;  // values without a short decimal form
    if (i != 2) f.frame_index = 3 * i;
    f.skeleton_in_sensor = SyntheticSkeletonInSensor(0.37 * i);
    f.skeleton_in_sensor.confidence[Index(Joint::kLeftElbow)] = 0.7 / 3;
    if (i == 1) f.skeleton_in_sensor.confidence[Index(Joint::kRightFoot)] = 0;
    frames.push_back(f);
  }
  Expected<SkeletonTrack> track = SkeletonTrack::Create(frames, "constructed");
  ASSERT_TRUE(track.ok());
  TempDir dir;
  const std::string path = (dir.path() / "track.json").string();
  ASSERT_TRUE(WriteSkeletonTrackJson(*track, path).ok());
  EXPECT_FALSE(fs::exists(path + ".partial"));
  Expected<SkeletonTrack> back = ReadSkeletonTrackJson(path);
  ASSERT_TRUE(back.ok()) << back.error().message;
  ASSERT_EQ(back->size(), frames.size());
  EXPECT_NE(back->description().find("constructed"), std::string::npos);
  for (size_t i = 0; i < frames.size(); ++i) {
    SCOPED_TRACE(i);
    const SkeletonTrackFrame& a = frames[i];
    const SkeletonTrackFrame& b = back->frames()[i];
    EXPECT_EQ(a.timestamp_s, b.timestamp_s);
    EXPECT_EQ(a.frame_index, b.frame_index);
    for (int j = 0; j < kJointCount; ++j) {
      EXPECT_EQ(a.skeleton_in_sensor.confidence[j], b.skeleton_in_sensor.confidence[j]);
      if (a.skeleton_in_sensor.confidence[j] > 0)
        EXPECT_EQ(a.skeleton_in_sensor.position[j], b.skeleton_in_sensor.position[j]);
      else
        EXPECT_EQ(b.skeleton_in_sensor.position[j], Eigen::Vector3d::Zero());
    }
  }
}

TEST(SkeletonTrackJsonTest, IndexOnlyTrackIsKeyedByIndex) {
  Expected<SkeletonTrack> track = ParseSkeletonTrackJson(
      Document(std::string(R"({"frame_index": 4, "joints": {)") + kHead + "}}"), "t.json");
  ASSERT_TRUE(track.ok()) << track.error().message;
  EXPECT_FALSE(track->keyed_by_timestamp());
  EXPECT_TRUE(track->ForFrame(4, 0).has_value());
  EXPECT_FALSE(track->ForFrame(3, 0).has_value());
}

TEST(SkeletonTrackJsonTest, NotJsonIsAnError) { ExpectCorrupt("{\"format\": ", "not valid JSON"); }

TEST(SkeletonTrackJsonTest, EmptyFileIsAnError) { ExpectCorrupt("", "not valid JSON"); }

TEST(SkeletonTrackJsonTest, WrongFormatIsAnError) {
  ExpectCorrupt(R"({"format": "bvh", "version": 1, "frame": "sensor", "frames": []})",
                "format = \"bvh\"");
}

TEST(SkeletonTrackJsonTest, LaterVersionIsUnsupported) {
  Expected<SkeletonTrack> track = ParseSkeletonTrackJson(
      R"({"format": "reenact-skeleton-track", "version": 2, "frame": "sensor", "frames": []})",
      "t.json");
  ASSERT_FALSE(track.ok());
  EXPECT_EQ(track.error().code, "unsupported");
}

TEST(SkeletonTrackJsonTest, WorldFrameIsRefused) {
  ExpectCorrupt(R"({"format": "reenact-skeleton-track", "version": 1, "frame": "world",
                    "frames": [{"frame_index": 0, "joints": {}}]})",
                "frame = \"world\"");
}

TEST(SkeletonTrackJsonTest, MissingFramesIsAnError) {
  ExpectCorrupt(R"({"format": "reenact-skeleton-track", "version": 1, "frame": "sensor"})",
                "missing field frames");
}

TEST(SkeletonTrackJsonTest, NoFramesIsAnError) { ExpectCorrupt(Document(""), "frames is empty"); }

TEST(SkeletonTrackJsonTest, ConfidenceOutOfRangeIsAnError) {
  ExpectCorrupt(Document(R"({"frame_index": 0, "joints": {"l_hand":
                    {"position": [0, 0, 2], "confidence": 2}}})"),
                "frames[0].joints.l_hand.confidence = 2 is outside [0, 1]");
}

TEST(SkeletonTrackJsonTest, UnknownJointIsAnError) {
  ExpectCorrupt(Document(R"({"frame_index": 0, "joints": {"l_wrist":
                    {"position": [0, 0, 2], "confidence": 1}}})"),
                "frames[0].joints.l_wrist is not one of our joints");
}

TEST(SkeletonTrackJsonTest, NonFiniteNumberIsAnError) {
  // JSON has no NaN or infinity: the literal is a syntax error, an overflowing number too.
  ExpectCorrupt(Document(R"({"frame_index": 0, "joints": {"head":
                    {"position": [0, NaN, 2], "confidence": 1}}})"),
                "not valid JSON");
  ExpectCorrupt(Document(R"({"frame_index": 0, "joints": {"head":
                    {"position": [0, 1e999, 2], "confidence": 1}}})"),
                "number overflow parsing '1e999'");
}

TEST(SkeletonTrackJsonTest, WrongTypesAreErrors) {
  ExpectCorrupt(Document(R"({"frame_index": 0, "joints": {"head":
                    {"position": [0, "1", 2], "confidence": 1}}})"),
                "frames[0].joints.head.position[1] must be a number");
  ExpectCorrupt(Document(R"({"frame_index": 0, "joints": {"head":
                    {"position": [0, 1], "confidence": 1}}})"),
                "frames[0].joints.head.position must have 3 elements");
  ExpectCorrupt(Document(R"({"frame_index": 1.5, "joints": {}})"),
                "frames[0].frame_index must be an integer");
  ExpectCorrupt(Document(R"({"frame_index": -1, "joints": {}})"),
                "frames[0].frame_index = -1 must be >= 0");
  ExpectCorrupt(Document(R"({"timestamp_s": "0", "joints": {}})"),
                "frames[0].timestamp_s must be a number");
  ExpectCorrupt(Document(R"({"frame_index": 0, "joints": []})"),
                "frames[0].joints must be an object");
  ExpectCorrupt(Document(R"({"frame_index": 0, "joints": {"head": {"confidence": 1}}})"),
                "missing field frames[0].joints.head.position");
}

TEST(SkeletonTrackJsonTest, FrameWithoutKeyIsAnError) {
  ExpectCorrupt(Document(R"({"joints": {}})"), "frames[0] has neither timestamp_s nor");
}

TEST(SkeletonTrackJsonTest, DuplicateTimestampIsAnError) {
  ExpectCorrupt(Document(R"({"timestamp_s": 1, "joints": {}}, {"timestamp_s": 1, "joints": {}})"),
                "frames[1].timestamp_s = 1 is the same as the previous frame's 1");
}

TEST(SkeletonTrackJsonTest, DecreasingTimestampIsAnError) {
  ExpectCorrupt(Document(R"({"timestamp_s": 2, "joints": {}}, {"timestamp_s": 1.5, "joints": {}})"),
                "frames[1].timestamp_s = 1.5 is before the previous frame's 2");
}

TEST(SkeletonTrackJsonTest, DuplicateFrameIndexIsAnError) {
  ExpectCorrupt(Document(R"({"frame_index": 3, "joints": {}}, {"frame_index": 3, "joints": {}})"),
                "frames[1].frame_index = 3 is not after frames[0].frame_index = 3");
}

TEST(SkeletonTrackJsonTest, MixedTimestampsAreAnError) {
  ExpectCorrupt(Document(R"({"timestamp_s": 1, "joints": {}}, {"frame_index": 3, "joints": {}})"),
                "frames[1] has no timestamp_s while frames[0] has one");
}

TEST(SkeletonTrackJsonTest, MissingFileIsNotFound) {
  TempDir dir;
  Expected<SkeletonTrack> track = ReadSkeletonTrackJson((dir.path() / "none.json").string());
  ASSERT_FALSE(track.ok());
  EXPECT_EQ(track.error().code, "not_found");
}

TEST(SkeletonTrackJsonTest, UnwritableDestinationIsAnIoError) {
  Expected<SkeletonTrack> track =
      ParseSkeletonTrackJson(Document(R"({"frame_index": 0, "joints": {}})"), "t.json");
  ASSERT_TRUE(track.ok());
  TempDir dir;
  const Status s = WriteSkeletonTrackJson(*track, (dir.path() / "no" / "t.json").string());
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, "io");
}

}  // namespace
}  // namespace reenact::capture
