#include "proto/clip/map_codec.h"

#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "common/error/check.h"

namespace reenact::proto {
namespace {

// n points uniformly in the box [-3, 7] x [0, 2] x [1, 5] (longest side 10 m), with random
// descriptors and observation counts.
ClipMap RandomMap(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(-3, 7), uy(0, 2), uz(1, 5);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<uint32_t> obs(1, 1000);
  ClipMap map;
  for (int i = 0; i < n; ++i) {
    MapPoint p;
    p.position_in_world = Eigen::Vector3d(ux(rng), uy(rng), uz(rng));
    for (auto& b : p.descriptor) b = static_cast<uint8_t>(byte(rng));
    p.observations = obs(rng);
    map.points.push_back(p);
  }
  // Pin the box so its longest side is exactly 10 m.
  map.points[0].position_in_world.x() = -3;
  map.points[1].position_in_world.x() = 7;
  return map;
}

// Derived independently from Draco's quantiser: a step of extent / (2^bits - 1), rounding to
// the nearest step (half a step), plus float32 slack of a few ulps of the extent.
double QuantisationBound(double extent, int bits) {
  return 0.5 * extent / (std::pow(2.0, bits) - 1) + 8 * extent * std::pow(2.0, -24);
}

void ExpectRoundTrip(const ClipMap& map, int bits, double extent) {
  MapCodecOptions options;
  options.position_quantization_bits = bits;
  const auto bytes = EncodeMap(map, options);
  ASSERT_TRUE(bytes.ok()) << bytes.error().message;
  const auto decoded = DecodeMap(*bytes);
  ASSERT_TRUE(decoded.ok()) << decoded.error().message;
  ASSERT_EQ(decoded->points.size(), map.points.size());
  const double bound = QuantisationBound(extent, bits);
  EXPECT_NEAR(MapPositionErrorBound(extent, bits), bound, 1e-6 * bound);
  double worst = 0;
  for (size_t i = 0; i < map.points.size(); ++i) {
    const MapPoint& a = map.points[i];
    const MapPoint& b = decoded->points[i];
    worst = std::max(worst, (a.position_in_world - b.position_in_world).cwiseAbs().maxCoeff());
    EXPECT_EQ(a.descriptor, b.descriptor) << i;
    EXPECT_EQ(a.observations, b.observations) << i;
  }
  EXPECT_LE(worst, bound) << "bits " << bits;
  // Coarse settings really quantise (the positions did go through Draco).
  if (bits <= 11) {
    EXPECT_GT(worst, 0.1 * bound) << "bits " << bits;
  }
}

TEST(ClipMapCodec, RoundTripWithinQuantisationBound) {
  const ClipMap map = RandomMap(2000, 7);
  for (int bits : {8, 11, 16, 20}) ExpectRoundTrip(map, bits, 10.0);
}

TEST(ClipMapCodec, KeepsPointOrder) {
  // Points 1 m apart in a shuffled order: each decoded position must be its own.
  ClipMap map;
  for (int i = 0; i < 50; ++i) {
    MapPoint p;
    p.position_in_world = Eigen::Vector3d((i * 37) % 50, 0, 0);
    p.descriptor.fill(static_cast<uint8_t>(i));
    p.observations = static_cast<uint32_t>(i);
    map.points.push_back(p);
  }
  const auto decoded = DecodeMap(*EncodeMap(map, MapCodecOptions{}));
  ASSERT_TRUE(decoded.ok()) << decoded.error().message;
  for (int i = 0; i < 50; ++i)
    EXPECT_NEAR(decoded->points[i].position_in_world.x(), (i * 37) % 50, 1e-3) << i;
}

TEST(ClipMapCodec, FarFromTheOriginKeepsPrecision) {
  // A map 2 km from the world origin: offsets from the box corner keep float precision.
  ClipMap map = RandomMap(300, 3);
  for (MapPoint& p : map.points) p.position_in_world += Eigen::Vector3d(2000, -1500, 700);
  ExpectRoundTrip(map, 16, 10.0);
}

TEST(ClipMapCodec, EmptyMapRoundTrips) {
  const auto bytes = EncodeMap(ClipMap{}, MapCodecOptions{});
  ASSERT_TRUE(bytes.ok()) << bytes.error().message;
  const auto decoded = DecodeMap(*bytes);
  ASSERT_TRUE(decoded.ok()) << decoded.error().message;
  EXPECT_TRUE(decoded->points.empty());
}

TEST(ClipMapCodec, SinglePointIsExact) {
  ClipMap map;
  map.points.push_back({Eigen::Vector3d(1.25, -2.5, 3.75), {}, 4});
  const auto decoded = DecodeMap(*EncodeMap(map, MapCodecOptions{}));
  ASSERT_TRUE(decoded.ok()) << decoded.error().message;
  ASSERT_EQ(decoded->points.size(), 1u);
  EXPECT_EQ(decoded->points[0].position_in_world, map.points[0].position_in_world);
  EXPECT_EQ(decoded->points[0].observations, 4u);
}

std::vector<uint8_t> GoodBytes() { return *EncodeMap(RandomMap(100, 11), MapCodecOptions{}); }

Error DecodeError(const std::vector<uint8_t>& bytes) {
  const auto decoded = DecodeMap(bytes);
  EXPECT_FALSE(decoded.ok());
  return decoded.ok() ? Error{} : decoded.error();
}

bool Contains(const Error& e, const std::string& text) {
  return e.message.find(text) != std::string::npos;
}

TEST(ClipMapCodec, RejectsTruncation) {
  const std::vector<uint8_t> bytes = GoodBytes();
  for (size_t size : {size_t{0}, size_t{2}, size_t{20}, size_t{47}, bytes.size() / 2, bytes.size() - 1}) {
    const Error e = DecodeError(std::vector<uint8_t>(bytes.begin(), bytes.begin() + size));
    EXPECT_EQ(e.code, "corrupt") << size << ": " << e.message;
  }
}

TEST(ClipMapCodec, RejectsBadMagic) {
  std::vector<uint8_t> bytes = GoodBytes();
  bytes[3] = 'Q';
  EXPECT_TRUE(Contains(DecodeError(bytes), "bad magic"));
}

TEST(ClipMapCodec, RejectsUnknownVersion) {
  std::vector<uint8_t> bytes = GoodBytes();
  bytes[4] = 9;
  EXPECT_EQ(DecodeError(bytes).code, "unsupported");
}

TEST(ClipMapCodec, RejectsTrailingBytes) {
  std::vector<uint8_t> bytes = GoodBytes();
  bytes.push_back(1);
  EXPECT_TRUE(Contains(DecodeError(bytes), "disagrees with 100 points"));
}

TEST(ClipMapCodec, RejectsPointCountDisagreeingWithSize) {
  std::vector<uint8_t> bytes = GoodBytes();
  bytes[8] = 101;  // point_count, little-endian
  EXPECT_TRUE(Contains(DecodeError(bytes), "disagrees with 101 points"));
}

TEST(ClipMapCodec, RejectsHugePointCountWithoutAllocating) {
  std::vector<uint8_t> bytes = GoodBytes();
  bytes[8] = bytes[9] = bytes[10] = 0xFF;
  bytes[11] = 0x00;  // 16777215 points claimed in a few kilobytes
  EXPECT_EQ(DecodeError(bytes).code, "corrupt");
}

TEST(ClipMapCodec, RejectsGarbageDracoStream) {
  std::vector<uint8_t> bytes = GoodBytes();
  std::fill(bytes.begin() + 48, bytes.begin() + 64, 0);  // the Draco header starts at 48
  EXPECT_TRUE(Contains(DecodeError(bytes), "Draco stream does not decode"));
}

TEST(ClipMapCodec, RejectsDracoLengthWithEmptyMap) {
  std::vector<uint8_t> bytes = *EncodeMap(ClipMap{}, MapCodecOptions{});
  bytes[40] = 1;  // draco_length = 1 with 0 points
  EXPECT_TRUE(Contains(DecodeError(bytes), "disagrees with 0 points"));
}

TEST(ClipMapCodec, EncodeRejectsNonFinitePosition) {
  ClipMap map = RandomMap(10, 1);
  map.points[4].position_in_world.y() = std::nan("");
  const auto bytes = EncodeMap(map, MapCodecOptions{});
  ASSERT_FALSE(bytes.ok());
  EXPECT_EQ(bytes.error().code, "invalid_argument");
  EXPECT_EQ(bytes.error().message, "map: point 4 has a non-finite position");
}

TEST(ClipMapCodec, EncodeRejectsHugeExtent) {
  ClipMap map = RandomMap(10, 1);
  map.points[2].position_in_world.z() = 1e7;
  const auto bytes = EncodeMap(map, MapCodecOptions{});
  ASSERT_FALSE(bytes.ok());
  EXPECT_EQ(bytes.error().code, "invalid_argument");
}

TEST(ClipMapCodec, OptionsCheckRanges) {
  EXPECT_THROW(MapCodecOptions{.position_quantization_bits = 0}.Check(), CheckError);
  EXPECT_THROW(MapCodecOptions{.position_quantization_bits = 31}.Check(), CheckError);
  EXPECT_THROW(MapCodecOptions{.draco_speed = 11}.Check(), CheckError);
  EXPECT_NO_THROW(MapCodecOptions{}.Check());
}

TEST(ClipMapCodec, SurvivesRandomCorruption) {
  // Whatever a damaged container holds, decoding returns a value or an error: no crash, no
  // exception, no read past the buffer (run under the sanitizers to see the last).
  const std::vector<uint8_t> good = GoodBytes();
  std::mt19937 rng(12345);
  std::uniform_int_distribution<size_t> where(0, good.size() - 1);
  std::uniform_int_distribution<int> value(0, 255);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<uint8_t> bytes = good;
    for (int k = 0; k <= trial % 4; ++k) bytes[where(rng)] = static_cast<uint8_t>(value(rng));
    EXPECT_NO_THROW((void)DecodeMap(bytes)) << trial;
  }
}

}  // namespace
}  // namespace reenact::proto
