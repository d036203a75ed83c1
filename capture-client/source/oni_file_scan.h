#pragma once
// A structural scan of an OpenNI recording (.oni) before OpenNI2 plays it: OpenNI2 2.2's
// file reader fails to open a truncated file without saying why and hangs on one without
// frames, and it does not expose whether the recording's depth is registered to colour.
//
// Container ("NI10", written by OpenNI 1.x and OpenNI2; little-endian, packed):
//   file header (24 bytes): magic "NI10", version {u8 major, u8 minor, u16 maintenance,
//                           u32 build}, u64 max timestamp, u32 max node id
//   records, back to back: u32 magic "NIR\0", u32 type, u32 node id, u32 fields size (this
//     header included), u32 payload size, undo position (u64; u32 in files older than
//     version 1.0.1.0, whose header is 24 bytes); then the fields, then the payload.
//   Record types used here: 0x02/0x0C/0x0D node added (fields: u32 name length with the
//   NUL, the name, u32 node type (2 depth, 3 image, 5 IR), u32 codec, u32 frame count in
//   0x0C/0x0D), 0x03 integer property (name as above, u32 size 8, u64 value), 0x06 general
//   property (name, u32 size, bytes), 0x0A new data (one frame), 0x0B end of recording.
// A file is complete when its records tile it exactly and an end record is present.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/error/expected.h"

namespace reenact::capture {

inline constexpr uint32_t kOniNodeTypeDepth = 2;
inline constexpr uint32_t kOniNodeTypeImage = 3;

struct OniNodeInfo {
  uint32_t id = 0;
  std::string name;            // "Depth1"
  uint32_t type = 0;           // OpenNI 1.x production node type
  uint32_t frame_count = 0;    // as declared by the node-added record (0 if not declared)
  uint32_t frame_records = 0;  // new-data records found for this node
  // OpenNI 1.x "AlternativeViewPoint": for a depth node, 1 = registered to the image node's
  // viewpoint; absent if the recording does not say.
  std::optional<uint64_t> alternative_view_point;
  bool has_cropping = false;  // "xnCropping" recorded (OpenNI2 2.2 yields no frames without)
};

struct OniFileSummary {
  uint64_t file_bytes = 0;
  int version_major = 0, version_minor = 0, version_maintenance = 0;
  std::vector<OniNodeInfo> nodes;
  uint64_t frame_records = 0;  // all nodes together

  const OniNodeInfo* FirstNodeOfType(uint32_t type) const;
};

// Errors, each saying what to do: "not_found" (no such file), "io" (unreadable), "corrupt"
// (not an ONI recording; a record that is malformed or runs past the end of the file, or a
// file without an end record: truncated), "empty" (a well-formed header but no frame).
Expected<OniFileSummary> ScanOniFile(const std::filesystem::path& path);

}  // namespace reenact::capture
