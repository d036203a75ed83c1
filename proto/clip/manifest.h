#pragma once
// The clip manifest: manifest.json of a clip directory and the body of a clip upload.
// JSON, versioned by "format_version" (this build reads and writes version 1).
//
// Layout (every field required unless marked optional; unknown fields are ignored so that a
// later minor addition does not break older readers):
//   {
//     "format_version": 1,
//     "title": "...", "description": "...", "author": "...",      (UTF-8, may be empty)
//     "capture_time": "2024-05-01T12:34:56Z",                      (ISO 8601 UTC, "Z",
//                                                                   optional fraction .sss)
//     "location": {"lat_deg", "lon_deg", "alt_m", "accuracy_m", "heading_deg" (optional)},
//     "color_camera": {"width", "height", "fx", "fy", "cx", "cy",
//                      "distortion": {"k1", "k2", "p1", "p2", "k3"}},
//     "depth_camera": { same },
//     "depth_scale_m": 0.001,
//     "world_up": [x, y, z],
//     "skeleton": {"joints": ["head", ...16 names in Joint order],
//                  "parts": {"head": ["head", "neck"], ... 11 parts}},
//     "radius_ratio": {"head": 0.35, ... one per part name},
//     "representative_frame": 0, "frame_count": 120, "frame_rate_hz": 30,
//     "duration_s": 4.0,                                            (frame_count / rate)
//     "map": {"point_count": 5000, "descriptor": "orb-256"},
//     "flagged_skeleton_frames": [17, 18],                          (optional, default [])
//     "parts": {"frames": [{"bytes": 12345, "sha256": "<64 hex>"}, ...],
//               "map": {"bytes": 67890, "sha256": "<64 hex>"}}
//   }
//
// ParseManifest validates everything and fails with Error{code, message}:
//   code "invalid_argument": malformed JSON, a key repeated within one object (at any depth),
//                            a missing field, a wrong type, a value out of range, a skeleton
//                            definition that differs from skeleton.h;
//   code "unsupported":      a format_version this build does not know.
// Messages name the field: "manifest: location.lat_deg = 95 is outside [-90, 90]".

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "common/error/expected.h"
#include "common/geometry/pinhole_camera.h"
#include "common/skeleton/skeleton.h"

namespace reenact::proto {

inline constexpr int kManifestFormatVersion = 1;
inline constexpr std::string_view kMapDescriptorOrb256 = "orb-256";

// Longest accepted title/author and description, in bytes of UTF-8.
inline constexpr size_t kMaxManifestNameBytes = 256;
inline constexpr size_t kMaxManifestDescriptionBytes = 16384;

// WGS84 position of the capture.
struct ClipLocation {
  double lat_deg = 0;     // [-90, 90]
  double lon_deg = 0;     // [-180, 180]
  double alt_m = 0;       // metres above the WGS84 ellipsoid; finite
  double accuracy_m = 0;  // horizontal 1-sigma accuracy, metres; finite, >= 0
  // Compass heading of the world frame's forward axis, degrees clockwise from north, in
  // [0, 360); absent if unknown.
  std::optional<double> heading_deg;
};

// Size and content hash of one stored part (a frame or the map).
struct PartInfo {
  uint64_t bytes = 0;  // > 0
  std::string sha256;  // 64 lowercase hex digits (Sha256Hex)
};

struct MapSummary {
  int64_t point_count = 0;                               // >= 0
  std::string descriptor = std::string(kMapDescriptorOrb256);  // only "orb-256" is known
};

struct ClipManifest {
  std::string title;
  std::string description;
  std::string author;
  std::string capture_time;  // ISO 8601 UTC, "YYYY-MM-DDTHH:MM:SS[.fff]Z"
  ClipLocation location;

  PinholeCamera color_camera;  // full sensor image intrinsics
  PinholeCamera depth_camera;
  double depth_scale_m = 0.001;  // metres per depth unit, (0, 1]; 0.001 for millimetres

  // Unit vector in the world frame pointing against gravity (|world_up| = 1 within 1e-3).
  Eigen::Vector3d world_up = Eigen::Vector3d(0, -1, 0);

  // Cylinder radius / bone length per body part (index = Index(BodyPart)), finite in (0, 2]:
  // radius = ratio * ||s_a - s_b|| (THESIS.md); the model builder in common/ fits it.
  std::array<double, kBodyPartCount> radius_ratio{};

  int64_t representative_frame = 0;  // [0, frame_count)
  int64_t frame_count = 0;           // >= 1, == frame_parts.size()
  double frame_rate_hz = 30;         // (0, 1000]
  MapSummary map;
  // Frames whose skeleton failed the capture's consistency check (bone lengths off the clip's
  // medians, left and right swapped): stored for the timeline, never chosen for texturing.
  // Ascending, distinct, each in [0, frame_count). Optional in the JSON (absent = none).
  std::vector<int64_t> flagged_skeleton_frames;

  std::vector<PartInfo> frame_parts;  // one per frame, in frame order
  PartInfo map_part;

  // Duration of the clip in seconds: frame_count frames each lasting 1 / frame_rate_hz.
  double DurationS() const { return static_cast<double>(frame_count) / frame_rate_hz; }
};

// Pretty JSON (2-space indent) in the layout above. Does not validate; ParseManifest of the
// result succeeds exactly when the manifest's values are in range.
std::string SerializeManifest(const ClipManifest& manifest);

// Parses and validates a manifest (see the top of this header for the error codes).
Expected<ClipManifest> ParseManifest(std::string_view json);

// True if text is "YYYY-MM-DDTHH:MM:SS[.f+]Z" with a real calendar date and time of day
// (seconds up to 60 for a leap second).
bool IsIso8601Utc(std::string_view text);

}  // namespace reenact::proto
