#pragma once
// Biovision Hierarchy (BVH) motion files: parsing and forward kinematics, in the file's own
// units and axes (no conversion here; bvh_motion.h maps a clip onto our skeleton).
//
// Format. HIERARCHY, then one or more ROOT blocks; a block is
//   { OFFSET x y z  CHANNELS n c_1 .. c_n  (JOINT name { ... } | End Site { OFFSET x y z })* }
// with c_i one of Xposition Yposition Zposition Xrotation Yrotation Zrotation, each at most
// once, in any order. Then MOTION, "Frames: N" (N >= 1), "Frame Time: T" (seconds, > 0) and N
// lines of numbers, one line per frame, one number per channel in hierarchy order. Keywords
// are case-sensitive as in the format's definition; CRLF line ends are accepted.
//
// Forward kinematics. A joint's transform relative to its parent is
//   parent_from_joint = Translation(OFFSET) * C_1 * ... * C_n
// with C_i the channel's translation (file units) or rotation (degrees, right-handed, about
// the axis of the frame so far), multiplied in the order the CHANNELS line lists them:
// "Zrotation Yrotation Xrotation" is R = Rz * Ry * Rx, and position channels listed first
// (as usual) translate along the parent's axes. Position
// channels therefore add to OFFSET (the CMU files' roots have OFFSET 0, where this agrees
// with readers that treat the root position as absolute). A joint's position is the origin
// of its frame; an End Site is a point at OFFSET in its parent's frame.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "common/error/expected.h"

namespace reenact::capture {

enum class BvhChannel { kXposition, kYposition, kZposition, kXrotation, kYrotation, kZrotation };

struct BvhJoint {
  std::string name;                                  // End Sites: "<parent name>/End Site"
  int parent = -1;                                   // index into BvhClip::joints; -1 for a ROOT
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // file units, parent's frame
  std::vector<BvhChannel> channels;                  // in file order; none for End Sites
  int first_channel = 0;                             // column of channels[0] in a frame's values
  bool end_site = false;
  int line = 0;  // 1-based line of the joint's ROOT / JOINT / End keyword
};

struct BvhClip {
  std::vector<BvhJoint> joints;  // file order: every parent before its children
  int channel_count = 0;         // sum of the joints' channel counts
  int frames = 0;                // >= 1
  double frame_time_s = 0;       // > 0
  // Frame-major: values[frame * channel_count + column], as in the file (degrees, units).
  std::vector<double> values;

  int frame_count() const { return frames; }
  double duration_s() const { return (frame_count() - 1) * frame_time_s; }
  // Indices of the joints that are not End Sites, in file order, and their names.
  std::vector<int> NamedJoints() const;
  std::vector<std::string> NamedJointNames() const;
};

// Parses BVH text. `source` names the input in error messages (e.g. the path). Errors
// ("corrupt"), each naming the 1-based line: a missing HIERARCHY / ROOT / MOTION section,
// an unexpected or missing token, a number that does not parse or is not finite, an unknown
// or repeated channel, a CHANNELS count that disagrees with the names listed, Frames < 1,
// Frame Time <= 0, a frame line whose value count differs from the channels declared, fewer
// frame lines than Frames declares (truncated file) or more.
Expected<BvhClip> ParseBvh(std::string_view text, std::string_view source = "BVH");

// Reads and parses a file. Errors: "not_found" / "io" when it cannot be read, else as
// ParseBvh, each message starting with the path.
Expected<BvhClip> ReadBvhFile(const std::filesystem::path& path);

// bvh_from_joint of every joint (End Sites included; an End Site's rotation is its
// parent's) at `frame`, in the file's units and axes. Throws CheckError on a frame out of
// range.
std::vector<Eigen::Isometry3d> BvhJointTransforms(const BvhClip& clip, int frame);
// The translations of BvhJointTransforms: every joint's position.
std::vector<Eigen::Vector3d> BvhJointPositions(const BvhClip& clip, int frame);

}  // namespace reenact::capture
