#pragma once
// The relocalisation map of a clip (static background points with ORB descriptors) and its
// binary container (.rmap).
//
// Container, all integers little-endian:
//   "RMAP"          4 bytes magic
//   version         u32, kMapFormatVersion (1)
//   point_count     u32, n (<= kMaxMapPoints)
//   quant_bits      u32, position quantisation bits used (informational, [1, 30])
//   origin          3 x f64, metres: the minimum corner of the positions' bounding box
//   draco_length    u64, bytes of the Draco stream (0 exactly when n == 0)
//   draco           Draco point cloud, sequential encoding (point order kept), one float32
//                   POSITION attribute holding position_in_world - origin, quantised
//                   explicitly over the cube [0, extent] with extent = the box's longest side
//   descriptors     n x 32 bytes, exact
//   observations    n x u32, exact
//   (nothing after)
//
// Position error bound. Draco maps each offset component v in [0, extent] to
// q = floor(v / delta + 1/2), delta = extent' / (2^bits - 1) with extent' = extent rounded up
// to float, and back to q * delta: at most delta / 2 away. Float32 arithmetic adds at most
// seven roundings of 2^-24 * extent each (offset, delta, the scaling, the +1/2, q to float,
// the product, extent'), so per axis
//   |decoded - original| <= extent / (2 (2^bits - 1)) + 2^-21 * extent.
//
// DecodeMap fails with Error{code, message}: "corrupt" for truncation, bad magic, counts or
// lengths that disagree with the size, a Draco stream that does not decode to n finite
// positions; "unsupported" for an unknown version. EncodeMap fails with "invalid_argument"
// for non-finite positions, a bounding box larger than kMaxMapExtentM, or too many points.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "common/error/expected.h"

namespace reenact::proto {

inline constexpr uint32_t kMapFormatVersion = 1;
inline constexpr uint32_t kMaxMapPoints = 1u << 24;
// Longest side of the bounding box a map may span, metres.
inline constexpr double kMaxMapExtentM = 1e5;

struct MapPoint {
  Eigen::Vector3d position_in_world = Eigen::Vector3d::Zero();  // metres, world frame
  std::array<uint8_t, 32> descriptor{};                          // ORB, 256 bits
  uint32_t observations = 0;  // number of keyframes that observed the point
};

struct ClipMap {
  std::vector<MapPoint> points;
};

struct MapCodecOptions {
  // Bits per position component, [1, 30]; default 16 (a 10 m room -> 0.08 mm steps).
  int position_quantization_bits = 16;
  // Draco speed trade-off, [0, 10]: 0 = smallest stream, 10 = fastest; default 5.
  int draco_speed = 5;
  // Throws CheckError unless every field is in range.
  void Check() const;
};

// Per-axis bound on |decoded - original| position error for a map whose bounding box's
// longest side is extent_m, encoded with `bits` (see the derivation above).
double MapPositionErrorBound(double extent_m, int bits);

Expected<std::vector<uint8_t>> EncodeMap(const ClipMap& map, const MapCodecOptions& options);
Expected<ClipMap> DecodeMap(std::span<const uint8_t> bytes);

}  // namespace reenact::proto
