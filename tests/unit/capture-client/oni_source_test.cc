// oni: and openni: sources. The real recording is ../shared/data/oni/kinect-room-12f.oni
// (a Kinect v1 recorded through OpenNI 1.x: 12 colour + 12 depth frames of a room, 640x480).
// The bad recordings are made from it in a temporary directory.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <thread>

#include "capture-client/source/frame_source.h"
#include "capture-client/source/oni_file_scan.h"
#include "capture-client/source/openni_runtime.h"
#include "capture-client/source/openni_source.h"
#include "tests/unit/capture-client/source_test_util.h"

namespace reenact::capture {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

constexpr double kPi = 3.14159265358979323846;

fs::path RealOni() { return testing::SharedData("oni/kinect-room-12f.oni"); }

#define REQUIRE_REAL_ONI()                                     \
  do {                                                         \
    if (!fs::exists(RealOni())) {                              \
      GTEST_SKIP() << RealOni() << " is absent (shared data)"; \
    }                                                          \
  } while (0)

// Offset of the value of the first integer property `name` (its u64 after the u32 size).
size_t IntPropertyValueOffset(const std::vector<char>& bytes, const std::string& name) {
  const std::string needle = name + '\0';
  const auto it = std::search(bytes.begin(), bytes.end(), needle.begin(), needle.end());
  return it == bytes.end() ? 0 : static_cast<size_t>(it - bytes.begin()) + needle.size() + 4;
}

TEST(CameraFromFieldOfView, FollowsThePinholeGeometry) {
  // 90 deg: the image edge is as far from the centre as the focal length.
  const PinholeCamera c = CameraFromFieldOfView(640, 480, kPi / 2, 2 * std::atan(0.75));
  EXPECT_NEAR(c.fx, 320, 1e-9);
  EXPECT_NEAR(c.fy, 320, 1e-9);
  EXPECT_DOUBLE_EQ(c.cx, 319.5);
  EXPECT_DOUBLE_EQ(c.cy, 239.5);
  EXPECT_TRUE(c.distortion.IsZero());
  // A point on the left edge of the field of view projects onto the left image border.
  const auto px = c.Project(Eigen::Vector3d(-std::tan(kPi / 4), 0, 1));
  ASSERT_TRUE(px.has_value());
  EXPECT_NEAR(px->x(), c.cx - 320, 1e-9);
}

TEST(OpenNiRuntime, InitialisesOnceFromManyThreads) {
  std::vector<std::thread> threads;
  std::vector<int> ok(8, 0);
  for (int i = 0; i < 8; ++i)
    threads.emplace_back([&ok, i] { ok[i] = InitializeOpenNi().ok() ? 1 : 0; });
  for (auto& t : threads) t.join();
  EXPECT_EQ(std::count(ok.begin(), ok.end(), 1), 8);
  // Debian's library loads its drivers from OpenNI2/Drivers next to itself.
  const fs::path drivers = OpenNiDriverDirectory();
  EXPECT_EQ(drivers.filename(), "Drivers");
  EXPECT_TRUE(fs::exists(drivers / "libOniFile.so.0") || fs::exists(drivers / "libOniFile.so"))
      << drivers;
}

TEST(OniSource, PlaysEveryFrameOfTheRealRecording) {
  REQUIRE_REAL_ONI();
  auto source = OpenFrameSource("oni:" + RealOni().string());
  ASSERT_TRUE(source.ok()) << source.error().message;
  const SensorInfo& info = (*source)->info();
  EXPECT_EQ(info.color_camera.width, 640);
  EXPECT_EQ(info.color_camera.height, 480);
  EXPECT_EQ(info.frame_count, 12);
  EXPECT_DOUBLE_EQ(info.frame_rate_hz, 30);
  // A Kinect v1 at 640x480: focal length between its colour (~525 px) and infrared (~580 px)
  // cameras, principal point at the centre.
  EXPECT_GT(info.color_camera.fx, 500);
  EXPECT_LT(info.color_camera.fx, 600);
  EXPECT_NEAR(info.color_camera.fx, info.color_camera.fy, 5);
  EXPECT_DOUBLE_EQ(info.color_camera.cx, 319.5);
  EXPECT_NE(info.description.find("registered"), std::string::npos) << info.description;

  int frames = 0;
  double last_t = -1;
  while (true) {
    auto next = (*source)->Next();
    ASSERT_TRUE(next.ok()) << next.error().message;
    if (!next->has_value()) break;
    const SensorFrame& f = **next;
    EXPECT_EQ(f.color.width, 640);
    EXPECT_EQ(f.color.height, 480);
    EXPECT_EQ(f.color.channels, 3);
    EXPECT_EQ(f.depth.width, 640);
    EXPECT_EQ(f.depth.height, 480);
    EXPECT_GT(f.timestamp_s, last_t);
    if (last_t >= 0) {
      EXPECT_NEAR(f.timestamp_s - last_t, 1 / 30.0, 0.005);  // no frame skipped
    }
    last_t = f.timestamp_s;
    // A room: most pixels have a reading, and most readings lie between 0.5 and 8 m.
    size_t valid = 0, plausible = 0;
    for (uint16_t d : f.depth.data) {
      valid += d > 0;
      plausible += d >= 500 && d <= 8000;
    }
    EXPECT_GT(valid, f.depth.data.size() / 2) << "frame " << frames;
    EXPECT_GT(plausible, valid * 9 / 10) << "frame " << frames;
    // Colour is an image, not a constant.
    const auto [lo, hi] = std::minmax_element(f.color.data.begin(), f.color.data.end());
    EXPECT_GT(*hi - *lo, 100);
    EXPECT_FALSE(f.world_from_sensor.has_value());  // a recording has no tracked pose
    ++frames;
  }
  EXPECT_EQ(frames, 12);
  // The end stays the end.
  auto after = (*source)->Next();
  ASSERT_TRUE(after.ok());
  EXPECT_FALSE(after->has_value());
}

TEST(OniSource, WorksFromAnyWorkingDirectory) {
  REQUIRE_REAL_ONI();
  TempDir tmp;
  const fs::path before = fs::current_path();
  fs::current_path(tmp.path());
  auto source = OpenNiSource::OpenFile(RealOni(), {});
  fs::current_path(before);
  ASSERT_TRUE(source.ok()) << source.error().message;
  auto first = (*source)->Next();
  ASSERT_TRUE(first.ok()) << first.error().message;
  EXPECT_TRUE(first->has_value());
}

TEST(OniSource, FieldOfViewOptionSetsTheIntrinsics) {
  REQUIRE_REAL_ONI();
  auto source = OpenFrameSource("oni:" + RealOni().string() + "?fov=62.7x48.6");
  ASSERT_TRUE(source.ok()) << source.error().message;
  const PinholeCamera& c = (*source)->info().color_camera;
  EXPECT_NEAR(c.fx, 320 / std::tan(62.7 / 2 * kPi / 180), 1e-9);
  EXPECT_NEAR(c.fy, 240 / std::tan(48.6 / 2 * kPi / 180), 1e-9);
}

TEST(OniSource, ScanReadsTheRecordingsStructure) {
  REQUIRE_REAL_ONI();
  auto scan = ScanOniFile(RealOni());
  ASSERT_TRUE(scan.ok()) << scan.error().message;
  const OniNodeInfo* depth = scan->FirstNodeOfType(kOniNodeTypeDepth);
  const OniNodeInfo* image = scan->FirstNodeOfType(kOniNodeTypeImage);
  ASSERT_NE(depth, nullptr);
  ASSERT_NE(image, nullptr);
  EXPECT_EQ(depth->frame_count, 12u);
  EXPECT_EQ(depth->frame_records, 12u);
  EXPECT_EQ(image->frame_records, 12u);
  ASSERT_TRUE(depth->alternative_view_point.has_value());
  EXPECT_EQ(*depth->alternative_view_point, 1u);  // README: depth registered to colour
  EXPECT_TRUE(depth->has_cropping);
}

TEST(OniSourceBadInput, HeaderOnlyRecordingHasNoFrames) {
  REQUIRE_REAL_ONI();
  TempDir tmp;
  // The file header alone, and the first 4 KiB (the device node's records, before any frame).
  for (size_t bytes : {size_t{24}, size_t{4096}}) {
    const fs::path file = tmp.path() / ("head" + std::to_string(bytes) + ".oni");
    testing::WritePrefix(RealOni(), file, bytes);
    auto source = OpenFrameSource("oni:" + file.string());
    ASSERT_FALSE(source.ok()) << bytes;
    EXPECT_EQ(source.error().code, "empty") << source.error().message;
    EXPECT_NE(source.error().message.find("no frames"), std::string::npos)
        << source.error().message;
    EXPECT_NE(source.error().message.find("record again"), std::string::npos);
  }
}

TEST(OniSourceBadInput, TruncatedRecordingSaysWhereItEnds) {
  REQUIRE_REAL_ONI();
  TempDir tmp;
  const fs::path file = tmp.path() / "half.oni";
  const size_t size = fs::file_size(RealOni());
  testing::WritePrefix(RealOni(), file, size / 2);
  auto source = OpenFrameSource("oni:" + file.string());
  ASSERT_FALSE(source.ok());
  EXPECT_EQ(source.error().code, "corrupt") << source.error().message;
  EXPECT_NE(source.error().message.find("truncated"), std::string::npos) << source.error().message;
  EXPECT_NE(source.error().message.find(std::to_string(size / 2)), std::string::npos)
      << source.error().message;
}

TEST(OniSourceBadInput, RecordingThatYieldsNoFrameTimesOut) {
  REQUIRE_REAL_ONI();
  TempDir tmp;
  // The same recording without its cropping property ("xnCropping" renamed): OpenNI2 2.2's
  // reader then yields no frame at all.
  std::vector<char> bytes = testing::ReadBytes(RealOni());
  const std::string from("xnCropping"), to("xnCroppinq");
  int renamed = 0;
  for (auto it = bytes.begin();
       (it = std::search(it, bytes.end(), from.begin(), from.end())) != bytes.end(); ++renamed)
    std::copy(to.begin(), to.end(), it);
  ASSERT_EQ(renamed, 2);
  const fs::path file = tmp.path() / "nocrop.oni";
  testing::WriteBytes(file, bytes);
  auto source = OpenFrameSource("oni:" + file.string() + "?timeout_ms=300");
  ASSERT_TRUE(source.ok()) << source.error().message;
  auto next = (*source)->Next();
  ASSERT_FALSE(next.ok());
  EXPECT_EQ(next.error().code, "timeout") << next.error().message;
  EXPECT_NE(next.error().message.find("cropping"), std::string::npos) << next.error().message;
}

TEST(OniSourceBadInput, DepthFramesOutOfOrderAreRefused) {
  // The sixth depth frame's record numbered 2: played with repeat on (the recording holds the
  // frames it declares), a frame that does not follow the one before is what a recording
  // started over looks like, and must not be taken for a new frame.
  REQUIRE_REAL_ONI();
  TempDir tmp;
  std::vector<char> bytes = testing::ReadBytes(RealOni());
  const auto scan = ScanOniFile(RealOni());
  ASSERT_TRUE(scan.ok()) << scan.error().message;
  const uint32_t depth_id = scan->FirstNodeOfType(kOniNodeTypeDepth)->id;
  // Records from the 24-byte file header: u32 magic, type, node id, fields size (header
  // included), payload size, u64 undo position, then a new-data record's u64 timestamp and
  // u32 frame number (oni_file_scan.h; this file's version has the 28-byte record header).
  size_t at = 24;
  int depth_frames = 0;
  bool patched = false;
  while (at + 28 <= bytes.size() && !patched) {
    uint32_t head[5];
    std::memcpy(head, bytes.data() + at, sizeof head);
    if (head[1] == 0x0A && head[2] == depth_id && ++depth_frames == 6) {
      const uint32_t two = 2;
      std::memcpy(bytes.data() + at + 28 + 8, &two, 4);
      patched = true;
    }
    at += static_cast<size_t>(head[3]) + head[4];
  }
  ASSERT_TRUE(patched);
  const fs::path file = tmp.path() / "unordered.oni";
  testing::WriteBytes(file, bytes);
  auto source = OpenFrameSource("oni:" + file.string() + "?timeout_ms=500");
  ASSERT_TRUE(source.ok()) << source.error().message;
  int frames = 0;
  Expected<std::optional<SensorFrame>> next = std::optional<SensorFrame>();
  while ((next = (*source)->Next()).ok() && next->has_value()) ++frames;
  ASSERT_FALSE(next.ok()) << frames << " frames and the end";
  EXPECT_EQ(next.error().code, "corrupt") << next.error().message;
  EXPECT_NE(next.error().message.find("does not follow"), std::string::npos)
      << next.error().message;
  EXPECT_LT(frames, 6);
}

TEST(OniSourceBadInput, UnregisteredDepthIsRefused) {
  REQUIRE_REAL_ONI();
  TempDir tmp;
  std::vector<char> bytes = testing::ReadBytes(RealOni());
  const size_t value = IntPropertyValueOffset(bytes, "AlternativeViewPoint");  // depth node's
  ASSERT_GT(value, 0u);
  ASSERT_EQ(bytes[value], 1);
  bytes[value] = 0;
  const fs::path file = tmp.path() / "unregistered.oni";
  testing::WriteBytes(file, bytes);
  auto source = OpenFrameSource("oni:" + file.string());
  ASSERT_FALSE(source.ok());
  EXPECT_EQ(source.error().code, "unsupported");
  EXPECT_NE(source.error().message.find("not registered"), std::string::npos)
      << source.error().message;
}

TEST(OniSourceBadInput, NotAnOniFile) {
  TempDir tmp;
  const fs::path file = tmp.path() / "notes.oni";
  testing::WriteText(file, "these are not the frames you are looking for\n");
  auto source = OpenFrameSource("oni:" + file.string());
  ASSERT_FALSE(source.ok());
  EXPECT_EQ(source.error().code, "corrupt");
  EXPECT_NE(source.error().message.find("not an OpenNI recording"), std::string::npos);
}

TEST(OniSourceBadInput, MissingFileAndMissingArgument) {
  auto missing = OpenFrameSource("oni:/nonexistent/room.oni");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().code, "not_found");
  EXPECT_NE(missing.error().message.find("/nonexistent/room.oni"), std::string::npos);
  auto bare = OpenFrameSource("oni:");
  ASSERT_FALSE(bare.ok());
  EXPECT_EQ(bare.error().code, "usage");
  auto option = OpenFrameSource("oni:x.oni?speed=2");
  ASSERT_FALSE(option.ok());
  EXPECT_EQ(option.error().code, "usage");
  EXPECT_NE(option.error().message.find("speed"), std::string::npos);
  auto fov = OpenFrameSource("oni:x.oni?fov=wide");
  ASSERT_FALSE(fov.ok());
  EXPECT_NE(fov.error().message.find("HxV"), std::string::npos);
}

TEST(OpenNiDeviceSource, NoDeviceIsAClearError) {
  auto source = OpenFrameSource("openni");
  if (source.ok()) GTEST_SKIP() << "an OpenNI2 device is connected";
  EXPECT_EQ(source.error().code, "not_found");
  EXPECT_EQ(source.error().message.rfind("no OpenNI2 device found", 0), 0u)
      << source.error().message;
  auto by_uri = OpenFrameSource("openni:1d27/0601@1/2");
  ASSERT_FALSE(by_uri.ok());
  EXPECT_EQ(by_uri.error().code, "not_found");
}

}  // namespace
}  // namespace reenact::capture
