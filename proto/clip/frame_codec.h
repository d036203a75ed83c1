#pragma once
// One stored frame of a clip and its binary container (.rfrm).
//
// Container, all integers little-endian:
//   "RFRM"            4 bytes magic
//   version           u32, kFrameFormatVersion (1)
//   header_length     u32, bytes of the JSON header that follows (<= kMaxFrameHeaderBytes)
//   header            UTF-8 JSON:
//     {"timestamp_s": t,
//      "world_from_sensor": [16 numbers, 4x4 row-major; rotation orthonormal within 1e-6,
//                            det +1, last row 0 0 0 1],
//      "skeleton": {"<joint name>": {"position": [x, y, z], "confidence": c}, ... all 16},
//      "crop": {"x", "y", "width", "height"},
//      "color": {"codec": "jpeg", "bytes": n}, "depth": {"codec": "png16", "bytes": n},
//      "mask": {"codec": "png8", "bytes": n}}
//   colour payload    JPEG (3 channels), then depth payload (16-bit greyscale PNG), then mask
//                     payload (8-bit greyscale PNG); the container ends right after the mask.
//
// DecodeFrame validates the container, the header and each image's own header (size,
// format) before decoding pixels, and fails with Error{code, message}:
//   code "corrupt":     truncated, bad magic, lengths past the end or trailing bytes,
//                       malformed header JSON or values out of range, an image whose size or
//                       format disagrees with the header, an image that does not decode;
//   code "unsupported": a container version this build does not know.

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Geometry>

#include "common/error/expected.h"
#include "common/image/image.h"
#include "common/skeleton/skeleton.h"

namespace reenact::proto {

inline constexpr uint32_t kFrameFormatVersion = 1;
inline constexpr uint32_t kMaxFrameHeaderBytes = 1 << 20;
// Largest crop side accepted by the decoder, pixels.
inline constexpr int kMaxFrameSide = 8192;

// A stored frame: the subject's crop rectangle of one sensor frame.
struct ClipFrame {
  double timestamp_s = 0;  // seconds, any fixed origin (finite)
  // Pose of the sensor (OpenCV camera frame) in the world (SLAM map) frame; thesis M_n^-1.
  Eigen::Isometry3d world_from_sensor = Eigen::Isometry3d::Identity();
  Skeleton skeleton_in_world;  // metres, world frame, per-joint confidence in [0, 1]
  // Top-left pixel of the crop rectangle in the full sensor image (>= 0).
  int crop_x = 0;
  int crop_y = 0;
  // All three of the crop's size (width x height), depth registered to colour.
  ImageRgb8 color;     // 3 channels, R G B
  ImageDepthMm depth;  // 1 channel, depth units (manifest depth_scale_m), 0 = no reading
  ImageGray8 mask;     // 1 channel, 0 background, 255 subject
};

struct FrameCodecOptions {
  // JPEG quality of the colour image, [1, 100]; default 92.
  int jpeg_quality = 92;
  // Throws CheckError unless every field is in range.
  void Check() const;
};

// Encodes a frame. Preconditions (CheckError otherwise): options valid; colour 3 channels,
// depth and mask 1 channel, all the same non-empty size no larger than kMaxFrameSide;
// crop_x, crop_y >= 0; timestamp, pose and joint positions finite, confidences in [0, 1],
// world_from_sensor a rotation (orthonormal within 1e-6, det +1) plus translation.
std::vector<uint8_t> EncodeFrame(const ClipFrame& frame, const FrameCodecOptions& options);

// Decodes and validates a .rfrm container (errors: see the top of this header).
Expected<ClipFrame> DecodeFrame(std::span<const uint8_t> bytes);

}  // namespace reenact::proto
