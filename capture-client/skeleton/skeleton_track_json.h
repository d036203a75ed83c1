#pragma once
// Our skeleton-track file: JSON, versioned, one 16-joint skeleton per frame in the sensor
// frame (OpenCV camera axes: x right, y down, z forward; metres). Example:
//   {
//     "format": "reenact-skeleton-track",
//     "version": 1,
//     "frame": "sensor",
//     "description": "hand-labelled, take 3",                (optional, free text)
//     "frames": [
//       {"timestamp_s": 0.000, "frame_index": 0,
//        "joints": {"head":  {"position": [0.02, -0.61, 2.48], "confidence": 1},
//                   "neck":  {"position": [0.02, -0.47, 2.50], "confidence": 0.8},
//                   ...}},
//       {"timestamp_s": 0.033, "joints": {...}},
//       ...
//     ]
//   }
// Fields:
// - "format" must be "reenact-skeleton-track", "version" 1 (a later version is refused with
//   code "unsupported"), "frame" "sensor" (the only frame a track can be in).
// - frames[i].timestamp_s (number, seconds) and/or frames[i].frame_index (integer >= 0):
//   every frame has a timestamp or none does; without timestamps every frame needs an
//   index. Both must increase strictly from frame to frame (see skeleton_track.h for how
//   a captured frame finds its skeleton).
// - frames[i].joints: an object keyed by our snake-case joint names (JointName: head, neck,
//   torso, waist, l_shoulder, l_elbow, l_hand, r_shoulder, r_elbow, r_hand, l_hip, l_knee,
//   l_foot, r_hip, r_knee, r_foot); each {"position": [x, y, z] (finite numbers, metres),
//   "confidence": c (number in [0, 1]; 0 = missing)}. A joint left out is missing; an empty
//   object is a frame in which the subject was not tracked. Left/right are the subject's own.
// - Unknown top-level and frame fields are ignored (later minor additions); unknown joint
//   names are errors (they are typos or another skeleton, never data to drop silently).
//
// Every problem is an Error with code "corrupt" naming the file, the frame and the field,
// e.g. "take3.json: frames[4].joints.l_hand.confidence = 2 is outside [0, 1]"; code
// "not_found"/"io" when the file cannot be read, "unsupported" for another format version.

#include <string>
#include <string_view>

#include "capture-client/skeleton/skeleton_track.h"
#include "common/error/expected.h"

namespace reenact::capture {

inline constexpr std::string_view kSkeletonTrackFormat = "reenact-skeleton-track";
inline constexpr int kSkeletonTrackVersion = 1;

// Parses the JSON text of a track; `name` (usually the file name) starts every message and
// the track's description.
Expected<SkeletonTrack> ParseSkeletonTrackJson(std::string_view text, const std::string& name,
                                               const SkeletonTrackLookupOptions& options = {});

// Reads and parses a track file.
Expected<SkeletonTrack> ReadSkeletonTrackJson(const std::string& path,
                                              const SkeletonTrackLookupOptions& options = {});

// The JSON text of a track (the layout above; numbers in shortest round-trip form, so a
// written track reads back bit-identical). Missing joints (confidence 0) are left out.
std::string SkeletonTrackToJson(const SkeletonTrack& track);

// Writes the track to `path` (through a temporary file renamed into place, so a reader
// never sees half a file). Errors: code "io".
Status WriteSkeletonTrackJson(const SkeletonTrack& track, const std::string& path);

}  // namespace reenact::capture
