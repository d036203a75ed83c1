#include "proto/clip/frame_codec.h"

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "common/error/check.h"

namespace reenact::proto {
namespace {

using nlohmann::json;

constexpr int kW = 96, kH = 128;

// A smooth colour gradient, depth with every kind of value (0, 1, 65535, a ramp) and a disc
// mask; a pose rotated 30 degrees about a tilted axis; a skeleton with one missing joint.
ClipFrame MakeFrame() {
  ClipFrame f;
  f.timestamp_s = 1305031102.175304;
  f.world_from_sensor = Eigen::Translation3d(0.25, -1.5, 3.125) *
                        Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d(1, 2, 3).normalized());
  for (int j = 0; j < kJointCount; ++j)
    f.skeleton_in_world.Set(static_cast<Joint>(j), Eigen::Vector3d(0.1 * j, -0.05 * j, 2.0 + j / 3.0),
                            (j + 1) / 16.0);
  f.skeleton_in_world.confidence[Index(Joint::kLeftFoot)] = 0;
  f.crop_x = 211;
  f.crop_y = 37;
  f.color = ImageRgb8(kW, kH, 3);
  f.depth = ImageDepthMm(kW, kH, 1);
  f.mask = ImageGray8(kW, kH, 1);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      f.color.at(x, y, 0) = static_cast<uint8_t>(40 + x);
      f.color.at(x, y, 1) = static_cast<uint8_t>(30 + y);
      f.color.at(x, y, 2) = static_cast<uint8_t>(200 - (x + y) / 2);
      f.depth.at(x, y) = static_cast<uint16_t>(x == 0 ? 0 : x == 1 ? 65535 : 500 + 37 * x + 251 * y);
      const int dx = x - kW / 2, dy = y - kH / 2;
      f.mask.at(x, y) = dx * dx + dy * dy < 40 * 40 ? 255 : 0;
    }
  return f;
}

TEST(ClipFrameCodec, RoundTripIsExactExceptJpegColour) {
  const ClipFrame f = MakeFrame();
  const std::vector<uint8_t> bytes = EncodeFrame(f, FrameCodecOptions{});
  const auto decoded = DecodeFrame(bytes);
  ASSERT_TRUE(decoded.ok()) << decoded.error().message;
  const ClipFrame& g = *decoded;
  EXPECT_EQ(g.timestamp_s, f.timestamp_s);
  EXPECT_EQ(g.world_from_sensor.matrix(), f.world_from_sensor.matrix());
  EXPECT_EQ(g.skeleton_in_world.position, f.skeleton_in_world.position);
  EXPECT_EQ(g.skeleton_in_world.confidence, f.skeleton_in_world.confidence);
  EXPECT_FALSE(g.skeleton_in_world.Has(Joint::kLeftFoot));
  EXPECT_EQ(g.crop_x, 211);
  EXPECT_EQ(g.crop_y, 37);
  ASSERT_EQ(g.color.width, kW);
  ASSERT_EQ(g.color.height, kH);
  ASSERT_EQ(g.color.channels, 3);
  EXPECT_EQ(g.depth.width, kW);
  EXPECT_EQ(g.depth.data, f.depth.data);  // lossless
  EXPECT_EQ(g.mask.data, f.mask.data);    // lossless
  double sum = 0;
  for (size_t i = 0; i < f.color.data.size(); ++i) sum += std::abs(int(g.color.data[i]) - int(f.color.data[i]));
  // A smooth gradient at quality 92 comes back within about one grey level on average.
  EXPECT_LT(sum / f.color.data.size(), 1.5);
}

TEST(ClipFrameCodec, KeepsRgbChannelOrder) {
  ClipFrame f = MakeFrame();
  // Left third pure red, middle pure green, right pure blue.
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c) f.color.at(x, y, c) = (x * 3 / kW == c) ? 255 : 0;
  const auto g = DecodeFrame(EncodeFrame(f, FrameCodecOptions{}));
  ASSERT_TRUE(g.ok()) << g.error().message;
  for (int c = 0; c < 3; ++c) {
    const int x = (2 * c + 1) * kW / 6, y = kH / 2;  // centre of each third
    for (int k = 0; k < 3; ++k) {
      if (k == c) EXPECT_GT(g->color.at(x, y, k), 235) << "channel " << k << " at x=" << x;
      else EXPECT_LT(g->color.at(x, y, k), 20) << "channel " << k << " at x=" << x;
    }
  }
}

TEST(ClipFrameCodec, ContainerStartsWithMagicAndVersion) {
  const std::vector<uint8_t> bytes = EncodeFrame(MakeFrame(), FrameCodecOptions{});
  ASSERT_GT(bytes.size(), 12u);
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + 4), "RFRM");
  EXPECT_EQ(bytes[4], 1);
  EXPECT_EQ(bytes[5] | bytes[6] | bytes[7], 0);
}

// The container taken apart as the header documents it, to build malformed variants.
struct Parts {
  std::vector<uint8_t> prefix;  // magic + version
  json header;
  std::vector<uint8_t> payload;  // colour, depth, mask
};

uint32_t LoadU32(const std::vector<uint8_t>& b, size_t at) {
  return b[at] | b[at + 1] << 8 | b[at + 2] << 16 | uint32_t(b[at + 3]) << 24;
}

Parts Split(const std::vector<uint8_t>& bytes) {
  const uint32_t n = LoadU32(bytes, 8);
  return {std::vector<uint8_t>(bytes.begin(), bytes.begin() + 8),
          json::parse(bytes.begin() + 12, bytes.begin() + 12 + n),
          std::vector<uint8_t>(bytes.begin() + 12 + n, bytes.end())};
}

std::vector<uint8_t> Join(const Parts& p, const std::string& header_text) {
  std::vector<uint8_t> out = p.prefix;
  const uint32_t n = static_cast<uint32_t>(header_text.size());
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(n >> (8 * i)));
  out.insert(out.end(), header_text.begin(), header_text.end());
  out.insert(out.end(), p.payload.begin(), p.payload.end());
  return out;
}
std::vector<uint8_t> Join(const Parts& p) { return Join(p, p.header.dump()); }

Error DecodeError(const std::vector<uint8_t>& bytes) {
  const auto decoded = DecodeFrame(bytes);
  EXPECT_FALSE(decoded.ok());
  return decoded.ok() ? Error{} : decoded.error();
}

template <typename Edit>
Error DecodeEdited(Edit edit) {
  Parts p = Split(EncodeFrame(MakeFrame(), FrameCodecOptions{}));
  edit(p);
  return DecodeError(Join(p));
}

bool Contains(const Error& e, const std::string& text) {
  return e.message.find(text) != std::string::npos;
}

TEST(ClipFrameCodec, SplitAndJoinReproduceTheContainer) {
  const std::vector<uint8_t> bytes = EncodeFrame(MakeFrame(), FrameCodecOptions{});
  const Parts p = Split(bytes);
  EXPECT_EQ(Join(p, std::string(bytes.begin() + 12, bytes.begin() + 12 + LoadU32(bytes, 8))), bytes);
}

TEST(ClipFrameCodec, RejectsTruncation) {
  const std::vector<uint8_t> bytes = EncodeFrame(MakeFrame(), FrameCodecOptions{});
  for (size_t size : {size_t{0}, size_t{3}, size_t{10}, size_t{40}, bytes.size() / 2, bytes.size() - 1}) {
    const Error e = DecodeError(std::vector<uint8_t>(bytes.begin(), bytes.begin() + size));
    EXPECT_EQ(e.code, "corrupt") << size;
    EXPECT_TRUE(Contains(e, "truncated")) << size << ": " << e.message;
  }
}

TEST(ClipFrameCodec, RejectsBadMagic) {
  std::vector<uint8_t> bytes = EncodeFrame(MakeFrame(), FrameCodecOptions{});
  bytes[0] = 'X';
  const Error e = DecodeError(bytes);
  EXPECT_EQ(e.code, "corrupt");
  EXPECT_TRUE(Contains(e, "bad magic"));
}

TEST(ClipFrameCodec, RejectsUnknownVersion) {
  std::vector<uint8_t> bytes = EncodeFrame(MakeFrame(), FrameCodecOptions{});
  bytes[4] = 2;
  EXPECT_EQ(DecodeError(bytes).code, "unsupported");
}

TEST(ClipFrameCodec, RejectsHeaderLengthPastTheEnd) {
  std::vector<uint8_t> bytes = EncodeFrame(MakeFrame(), FrameCodecOptions{});
  const uint32_t n = static_cast<uint32_t>(bytes.size());  // header claims the whole file
  for (int i = 0; i < 4; ++i) bytes[8 + i] = static_cast<uint8_t>(n >> (8 * i));
  EXPECT_TRUE(Contains(DecodeError(bytes), "runs past the end"));
}

TEST(ClipFrameCodec, RejectsPayloadLengthPastTheEnd) {
  const Error e = DecodeEdited([](Parts& p) { p.header["mask"]["bytes"] = p.header["mask"]["bytes"].get<int>() + 1; });
  EXPECT_TRUE(Contains(e, "payload lengths run past the end")) << e.message;
}

TEST(ClipFrameCodec, RejectsTrailingBytes) {
  std::vector<uint8_t> bytes = EncodeFrame(MakeFrame(), FrameCodecOptions{});
  bytes.push_back(0);
  EXPECT_TRUE(Contains(DecodeError(bytes), "1 unexpected bytes"));
}

TEST(ClipFrameCodec, RejectsHeaderThatIsNotJson) {
  Parts p = Split(EncodeFrame(MakeFrame(), FrameCodecOptions{}));
  EXPECT_TRUE(Contains(DecodeError(Join(p, "{\"timestamp_s\": ")), "not valid JSON"));
}

TEST(ClipFrameCodec, RejectsMissingHeaderField) {
  const Error e = DecodeEdited([](Parts& p) { p.header.erase("crop"); });
  EXPECT_EQ(e.message, "frame: header: missing field crop");
}

TEST(ClipFrameCodec, RejectsNonFinitePose) {
  // JSON has no infinity: a number that overflows a double is the only way to write one.
  Parts p = Split(EncodeFrame(MakeFrame(), FrameCodecOptions{}));
  std::string text = p.header.dump();
  const std::string key = "\"world_from_sensor\":[";
  const size_t first = text.find(key) + key.size();
  text.replace(first, text.find(',', first) - first, "1e999");
  const Error e = DecodeError(Join(p, text));
  EXPECT_EQ(e.code, "corrupt");
  EXPECT_TRUE(Contains(e, "world_from_sensor[0] must be finite") || Contains(e, "not valid JSON"))
      << e.message;
}

TEST(ClipFrameCodec, RejectsPoseThatIsNotRigid) {
  const Error e = DecodeEdited([](Parts& p) { p.header["world_from_sensor"][0] = 2.0; });
  EXPECT_EQ(e.message, "frame: header: world_from_sensor has a rotation that is not orthonormal");
}

TEST(ClipFrameCodec, RejectsReflectedPose) {
  const Error e = DecodeEdited([](Parts& p) {
    json m = json::array({-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1});
    p.header["world_from_sensor"] = m;
  });
  EXPECT_TRUE(Contains(e, "determinant -1")) << e.message;
}

TEST(ClipFrameCodec, RejectsConfidenceOutOfRange) {
  const Error e = DecodeEdited([](Parts& p) { p.header["skeleton"]["r_knee"]["confidence"] = 1.5; });
  EXPECT_EQ(e.message, "frame: header: skeleton.r_knee.confidence = 1.5 is outside [0, 1]");
}

TEST(ClipFrameCodec, RejectsUnknownJoint) {
  const Error e = DecodeEdited([](Parts& p) {
    p.header["skeleton"]["tail"] = p.header["skeleton"]["head"];
  });
  EXPECT_EQ(e.message, "frame: header: skeleton names unknown joint \"tail\"");
}

TEST(ClipFrameCodec, RejectsMissingJoint) {
  const Error e = DecodeEdited([](Parts& p) { p.header["skeleton"].erase("waist"); });
  EXPECT_EQ(e.message, "frame: header: missing field skeleton.waist");
}

TEST(ClipFrameCodec, RejectsCropSizeDisagreeingWithImages) {
  const Error e = DecodeEdited([](Parts& p) { p.header["crop"]["width"] = kW + 1; });
  EXPECT_EQ(e.message, "frame: colour image is 96x128 but the crop is 97x128");
}

TEST(ClipFrameCodec, RejectsNegativeCropOrigin) {
  const Error e = DecodeEdited([](Parts& p) { p.header["crop"]["x"] = -1; });
  EXPECT_TRUE(Contains(e, "crop.x = -1 is outside")) << e.message;
}

TEST(ClipFrameCodec, RejectsHugeCrop) {
  const Error e = DecodeEdited([](Parts& p) { p.header["crop"]["height"] = 100000; });
  EXPECT_TRUE(Contains(e, "crop.height = 100000 is outside [1, 8192]")) << e.message;
}

TEST(ClipFrameCodec, RejectsMaskOfTheWrongPixelFormat) {
  const ClipFrame f = MakeFrame();
  const std::vector<uint8_t> good = EncodeFrame(f, FrameCodecOptions{});
  Parts p = Split(good);
  // Replace the mask by a 3-channel PNG of the right size.
  std::vector<uint8_t> rgb_png;
  ASSERT_TRUE(cv::imencode(".png", cv::Mat(kH, kW, CV_8UC3, cv::Scalar(255, 255, 255)), rgb_png));
  const size_t mask_bytes = p.header["mask"]["bytes"].get<size_t>();
  p.payload.resize(p.payload.size() - mask_bytes);
  p.payload.insert(p.payload.end(), rgb_png.begin(), rgb_png.end());
  p.header["mask"]["bytes"] = rgb_png.size();
  EXPECT_EQ(DecodeError(Join(p)).message, "frame: mask image has the wrong pixel format");
}

TEST(ClipFrameCodec, RejectsGarbageImagePayload) {
  Parts p = Split(EncodeFrame(MakeFrame(), FrameCodecOptions{}));
  const size_t color_bytes = p.header["color"]["bytes"].get<size_t>();
  std::fill(p.payload.begin(), p.payload.begin() + color_bytes, 0x5A);
  EXPECT_EQ(DecodeError(Join(p)).message, "frame: colour payload is not a readable image");
}

TEST(ClipFrameCodec, RejectsWrongCodecName) {
  const Error e = DecodeEdited([](Parts& p) { p.header["depth"]["codec"] = "png8"; });
  EXPECT_EQ(e.message, "frame: header: depth.codec = \"png8\" but must be \"png16\"");
}

TEST(ClipFrameCodec, EncodeChecksPreconditions) {
  ClipFrame f = MakeFrame();
  f.mask = ImageGray8(kW, kH - 1, 1);
  EXPECT_THROW(EncodeFrame(f, FrameCodecOptions{}), CheckError);
  EXPECT_THROW(EncodeFrame(MakeFrame(), FrameCodecOptions{.jpeg_quality = 0}), CheckError);
  ClipFrame scaled = MakeFrame();
  scaled.world_from_sensor.matrix()(0, 0) = 3;
  EXPECT_THROW(EncodeFrame(scaled, FrameCodecOptions{}), CheckError);
}

TEST(ClipFrameCodec, SurvivesRandomCorruption) {
  // Whatever a damaged container holds, decoding returns a value or an error: no crash, no
  // exception, no read past the buffer (run under the sanitizers to see the last).
  const std::vector<uint8_t> good = EncodeFrame(MakeFrame(), FrameCodecOptions{});
  std::mt19937 rng(12345);
  std::uniform_int_distribution<size_t> where(0, good.size() - 1);
  std::uniform_int_distribution<int> value(0, 255);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<uint8_t> bytes = good;
    for (int k = 0; k <= trial % 4; ++k) bytes[where(rng)] = static_cast<uint8_t>(value(rng));
    EXPECT_NO_THROW((void)DecodeFrame(bytes)) << trial;
  }
}

}  // namespace
}  // namespace reenact::proto
