#include "proto/clip/clip_directory.h"

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "proto/clip/content_hash.h"

namespace reenact::proto {
namespace {

namespace fs = std::filesystem;

class ClipDirectoryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("reenact_clip_test_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
    for (int i = 0; i < 3; ++i) {
      ClipFrame f;
      f.timestamp_s = i / 30.0;
      f.crop_x = 10 * i;
      f.color = ImageRgb8(8, 6, 3, static_cast<uint8_t>(50 * i));
      f.depth = ImageDepthMm(8, 6, 1, static_cast<uint16_t>(1000 + i));
      f.mask = ImageGray8(8, 6, 1, 255);
      frames_.push_back(EncodeFrame(f, FrameCodecOptions{}));
    }
    ClipMap map;
    map.points.push_back({Eigen::Vector3d(1, 2, 3), {}, 5});
    map.points.push_back({Eigen::Vector3d(-1, 0, 4), {}, 2});
    map_ = *EncodeMap(map, MapCodecOptions{});

    manifest_.title = "test";
    manifest_.capture_time = "2024-05-01T12:00:00Z";
    manifest_.color_camera = PinholeCamera::KinectLike();
    manifest_.depth_camera = PinholeCamera::KinectLike();
    manifest_.radius_ratio.fill(0.2);
    manifest_.map.point_count = 2;
    FillPartHashes(manifest_, frames_, map_);
  }
  void TearDown() override { fs::remove_all(root_); }

  // Names in root_ other than `keep`.
  std::vector<std::string> Leftovers(const std::string& keep = "") const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(root_))
      if (entry.path().filename() != keep) names.push_back(entry.path().filename().string());
    return names;
  }

  fs::path root_;
  std::vector<std::vector<uint8_t>> frames_;
  std::vector<uint8_t> map_;
  ClipManifest manifest_;
};

std::vector<uint8_t> ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

TEST_F(ClipDirectoryTest, FillPartHashesSetsSizesAndHashes) {
  EXPECT_EQ(manifest_.frame_count, 3);
  ASSERT_EQ(manifest_.frame_parts.size(), 3u);
  EXPECT_EQ(manifest_.frame_parts[1].bytes, frames_[1].size());
  EXPECT_EQ(manifest_.frame_parts[1].sha256, Sha256Hex(frames_[1]));
  EXPECT_EQ(manifest_.map_part.bytes, map_.size());
  EXPECT_EQ(manifest_.map_part.sha256, Sha256Hex(map_));
}

TEST_F(ClipDirectoryTest, WritesTheDocumentedLayoutAndReadsItBack) {
  const fs::path dir = root_ / "nested" / "clip";
  const Status written = WriteClipDirectory(dir, manifest_, frames_, map_);
  ASSERT_TRUE(written.ok()) << written.error().message;
  EXPECT_TRUE(fs::is_regular_file(dir / "manifest.json"));
  EXPECT_EQ(ReadFile(dir / "frames" / "000002.rfrm"), frames_[2]);
  EXPECT_EQ(ReadFile(dir / "map.rmap"), map_);
  EXPECT_EQ(ClipFramePath(dir, 42), dir / "frames" / "000042.rfrm");
  EXPECT_EQ(std::vector<std::string>{"clip"}, [&] {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(root_ / "nested")) names.push_back(e.path().filename());
    return names;
  }());  // no temporary directory left behind

  const auto clip = ReadClipDirectory(dir);
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  EXPECT_EQ(clip->manifest().title, "test");
  EXPECT_EQ(clip->manifest().frame_count, 3);
  for (int i = 0; i < 3; ++i) {
    const auto bytes = clip->ReadFrameBytes(i);
    ASSERT_TRUE(bytes.ok()) << bytes.error().message;
    EXPECT_EQ(*bytes, frames_[i]);
  }
  const auto frame = clip->ReadFrame(1);
  ASSERT_TRUE(frame.ok()) << frame.error().message;
  EXPECT_EQ(frame->crop_x, 10);
  EXPECT_EQ(frame->depth.at(3, 3), 1001);
  const auto map = clip->ReadMap();
  ASSERT_TRUE(map.ok()) << map.error().message;
  ASSERT_EQ(map->points.size(), 2u);
  EXPECT_EQ(map->points[1].observations, 2u);
}

TEST_F(ClipDirectoryTest, FlippedByteIsAHashMismatch) {
  const fs::path dir = root_ / "clip";
  ASSERT_TRUE(WriteClipDirectory(dir, manifest_, frames_, map_).ok());
  std::vector<uint8_t> bytes = frames_[1];
  bytes[bytes.size() / 2] ^= 0x01;
  std::ofstream(dir / "frames" / "000001.rfrm", std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  const auto clip = ReadClipDirectory(dir);
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  EXPECT_TRUE(clip->ReadFrameBytes(0).ok());
  const auto bad = clip->ReadFrameBytes(1);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().code, "corrupt");
  EXPECT_NE(bad.error().message.find("does not match its SHA-256"), std::string::npos);
}

TEST_F(ClipDirectoryTest, TruncatedPartIsASizeMismatch) {
  const fs::path dir = root_ / "clip";
  ASSERT_TRUE(WriteClipDirectory(dir, manifest_, frames_, map_).ok());
  fs::resize_file(dir / "map.rmap", map_.size() - 1);
  const auto bad = ReadClipDirectory(dir)->ReadMapBytes();
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().code, "corrupt");
  EXPECT_NE(bad.error().message.find("bytes but the manifest says"), std::string::npos);
}

TEST_F(ClipDirectoryTest, MissingFrameFailsOnOpen) {
  const fs::path dir = root_ / "clip";
  ASSERT_TRUE(WriteClipDirectory(dir, manifest_, frames_, map_).ok());
  fs::remove(dir / "frames" / "000002.rfrm");
  const auto clip = ReadClipDirectory(dir);
  ASSERT_FALSE(clip.ok());
  EXPECT_EQ(clip.error().code, "not_found");
  EXPECT_NE(clip.error().message.find("000002.rfrm"), std::string::npos);
}

TEST_F(ClipDirectoryTest, MissingManifestIsNotFound) {
  const auto clip = ReadClipDirectory(root_ / "nothing-here");
  ASSERT_FALSE(clip.ok());
  EXPECT_EQ(clip.error().code, "not_found");
}

TEST_F(ClipDirectoryTest, DamagedManifestIsRejected) {
  const fs::path dir = root_ / "clip";
  ASSERT_TRUE(WriteClipDirectory(dir, manifest_, frames_, map_).ok());
  std::ofstream(dir / "manifest.json", std::ios::trunc) << "{\"format_version\": 1}";
  const auto clip = ReadClipDirectory(dir);
  ASSERT_FALSE(clip.ok());
  EXPECT_EQ(clip.error().code, "invalid_argument");
  EXPECT_NE(clip.error().message.find("missing field"), std::string::npos);
}

TEST_F(ClipDirectoryTest, FrameIndexOutOfRange) {
  const fs::path dir = root_ / "clip";
  ASSERT_TRUE(WriteClipDirectory(dir, manifest_, frames_, map_).ok());
  const auto clip = ReadClipDirectory(dir);
  EXPECT_EQ(clip->ReadFrameBytes(3).error().code, "invalid_argument");
  EXPECT_EQ(clip->ReadFrameBytes(-1).error().code, "invalid_argument");
}

TEST_F(ClipDirectoryTest, RefusesToReplaceAnExistingDirectory) {
  const fs::path dir = root_ / "clip";
  fs::create_directory(dir);
  std::ofstream(dir / "keep.txt") << "mine";
  const Status s = WriteClipDirectory(dir, manifest_, frames_, map_);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, "already_exists");
  EXPECT_TRUE(fs::exists(dir / "keep.txt"));
  EXPECT_EQ(Leftovers("clip"), std::vector<std::string>{});
}

TEST_F(ClipDirectoryTest, PartsThatDisagreeWithTheManifestWriteNothing) {
  std::vector<std::vector<uint8_t>> frames = frames_;
  frames[0].push_back(0);
  const Status s = WriteClipDirectory(root_ / "clip", manifest_, frames, map_);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, "invalid_argument");
  EXPECT_NE(s.error().message.find("frame 0 differs"), std::string::npos);
  frames.pop_back();
  EXPECT_FALSE(WriteClipDirectory(root_ / "clip", manifest_, frames, map_).ok());
  EXPECT_EQ(Leftovers(), std::vector<std::string>{});
}

TEST_F(ClipDirectoryTest, InvalidManifestWritesNothing) {
  ClipManifest bad = manifest_;
  bad.location.lat_deg = 91;
  const Status s = WriteClipDirectory(root_ / "clip", bad, frames_, map_);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().message, "manifest: location.lat_deg = 91 is outside [-90, 90]");
  EXPECT_EQ(Leftovers(), std::vector<std::string>{});
}

TEST_F(ClipDirectoryTest, FileSystemRefusalIsAnIoError) {
  std::ofstream(root_ / "plain-file") << "not a directory";
  const Status s = WriteClipDirectory(root_ / "plain-file" / "clip", manifest_, frames_, map_);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, "io");
  EXPECT_EQ(Leftovers("plain-file"), std::vector<std::string>{});
}

}  // namespace
}  // namespace reenact::proto
