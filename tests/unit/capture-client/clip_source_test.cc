// clip: source: a clip written from constructed frames is replayed as full sensor frames.
#include "capture-client/source/clip_source.h"

#include <gtest/gtest.h>

#include "capture-client/source/frame_source.h"
#include "proto/clip/clip_directory.h"
#include "tests/unit/capture-client/source_test_util.h"

namespace reenact::capture {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

// Two frames: crops of 8x6 at (10, 20) and (30, 5) of a 64x48 sensor, each filled with its
// own values; a skeleton with the head at a known place; poses translated along x.
fs::path WriteTestClip(const fs::path& dir, double depth_scale_m) {
  std::vector<std::vector<uint8_t>> frames;
  for (int i = 0; i < 2; ++i) {
    proto::ClipFrame f;
    f.timestamp_s = 5 + i / 30.0;
    f.world_from_sensor = Eigen::Isometry3d(Eigen::Translation3d(0.5 * i, 0, 0));
    f.skeleton_in_world[Joint::kHead] = Eigen::Vector3d(1, 2, 3 + i);
    f.skeleton_in_world.confidence[Index(Joint::kHead)] = 1;
    f.crop_x = i == 0 ? 10 : 30;
    f.crop_y = i == 0 ? 20 : 5;
    f.color = ImageRgb8(8, 6, 3, static_cast<uint8_t>(100 + 50 * i));
    f.depth = ImageDepthMm(8, 6, 1, static_cast<uint16_t>(1000 + i));
    f.mask = ImageGray8(8, 6, 1, 255);
    f.mask.at(0, 0) = 0;
    frames.push_back(proto::EncodeFrame(f, proto::FrameCodecOptions{}));
  }
  proto::ClipMap map;
  map.points.push_back({Eigen::Vector3d(1, 2, 3), {}, 5});
  const std::vector<uint8_t> map_bytes = *proto::EncodeMap(map, proto::MapCodecOptions{});
  proto::ClipManifest manifest;
  manifest.title = "two crops";
  manifest.capture_time = "2024-05-01T12:00:00Z";
  manifest.color_camera = {64, 48, 50, 50, 31.5, 23.5, {}};
  manifest.depth_camera = manifest.color_camera;
  manifest.depth_scale_m = depth_scale_m;
  manifest.radius_ratio.fill(0.2);
  manifest.map.point_count = 1;
  manifest.frame_rate_hz = 30;
  proto::FillPartHashes(manifest, frames, map_bytes);
  const Status written = proto::WriteClipDirectory(dir, manifest, frames, map_bytes);
  EXPECT_TRUE(written.ok()) << written.error().message;
  return dir;
}

TEST(ClipSource, PlacesCropsBackIntoFullFrames) {
  TempDir tmp;
  const fs::path dir = WriteTestClip(tmp.path() / "clip", 0.001);
  auto source = OpenFrameSource("clip:" + dir.string());
  ASSERT_TRUE(source.ok()) << source.error().message;
  const SensorInfo& info = (*source)->info();
  EXPECT_EQ(info.frame_count, 2);
  EXPECT_EQ(info.color_camera.width, 64);
  EXPECT_DOUBLE_EQ(info.depth_scale_m, 0.001);
  EXPECT_NE(info.description.find("two crops"), std::string::npos);
  for (int i = 0; i < 2; ++i) {
    auto next = (*source)->Next();
    ASSERT_TRUE(next.ok()) << next.error().message;
    ASSERT_TRUE(next->has_value());
    const SensorFrame& f = **next;
    const int x0 = i == 0 ? 10 : 30, y0 = i == 0 ? 20 : 5;
    EXPECT_EQ(f.color.width, 64);
    EXPECT_EQ(f.depth.height, 48);
    ASSERT_TRUE(f.person_mask.has_value());
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 64; ++x) {
        const bool inside = x >= x0 && x < x0 + 8 && y >= y0 && y < y0 + 6;
        ASSERT_EQ(f.depth.at(x, y), inside ? 1000 + i : 0) << x << "," << y;
        ASSERT_EQ(f.person_mask->at(x, y), inside && !(x == x0 && y == y0) ? 255 : 0);
        if (!inside) {
          ASSERT_EQ(f.color.at(x, y, 1), 0);
        }
      }
    // JPEG of a flat patch: within a few levels.
    EXPECT_NEAR(f.color.at(x0 + 4, y0 + 3, 1), 100 + 50 * i, 3);
    EXPECT_NEAR(f.timestamp_s, 5 + i / 30.0, 1e-9);
    ASSERT_TRUE(f.world_from_sensor.has_value());
    EXPECT_NEAR(f.world_from_sensor->translation().x(), 0.5 * i, 1e-12);
    ASSERT_TRUE(f.skeleton_in_world.has_value());
    EXPECT_NEAR((*f.skeleton_in_world)[Joint::kHead].z(), 3 + i, 1e-9);
  }
  auto end = (*source)->Next();
  ASSERT_TRUE(end.ok());
  EXPECT_FALSE(end->has_value());
}

TEST(ClipSource, ConvertsOtherDepthUnitsToMillimetres) {
  TempDir tmp;
  const fs::path dir = WriteTestClip(tmp.path() / "clip", 0.002);  // 2 mm per unit
  auto source = ClipSource::Open(dir);
  ASSERT_TRUE(source.ok()) << source.error().message;
  EXPECT_DOUBLE_EQ((*source)->info().depth_scale_m, 0.001);
  auto next = (*source)->Next();
  ASSERT_TRUE(next.ok());
  EXPECT_EQ((*next)->depth.at(12, 22), 2000);
  EXPECT_EQ((*next)->depth.at(0, 0), 0);
}

TEST(ClipSourceBadInput, MissingAndDamagedClips) {
  TempDir tmp;
  auto missing = OpenFrameSource("clip:" + (tmp.path() / "none").string());
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().message.rfind("clip:", 0), 0u) << missing.error().message;

  const fs::path dir = WriteTestClip(tmp.path() / "clip", 0.001);
  std::vector<char> bytes = testing::ReadBytes(proto::ClipFramePath(dir, 1));
  bytes[bytes.size() / 2] ^= 0x5a;
  testing::WriteBytes(proto::ClipFramePath(dir, 1), bytes);
  auto source = OpenFrameSource("clip:" + dir.string());
  ASSERT_TRUE(source.ok()) << source.error().message;
  ASSERT_TRUE((*source)->Next().ok());
  auto damaged = (*source)->Next();
  ASSERT_FALSE(damaged.ok());
  EXPECT_EQ(damaged.error().code, "corrupt");
  EXPECT_NE(damaged.error().message.find("frame 1"), std::string::npos);
}

}  // namespace
}  // namespace reenact::capture
