#pragma once
// Opens an imported skeleton track from its command-line form (reenact-capture record
// --skeleton SPEC):
//   json:FILE[?OPTIONS]      our JSON track (skeleton_track_json.h)
//   kinect:FILE[?OPTIONS]    a Kinect v1 20-joint text track: UTKinect joints_sXX_eYY.txt,
//                            MSR Action3D aXX_sYY_eZZ_skeleton3D.txt, MSR DailyActivity3D
//                            aXX_sYY_eZZ_skeleton.txt or UTD-MHAD skeleton.txt, detected from
//                            the content (kinect_v1_skeleton.h)
//   FILE.json                the same as json:FILE.json
// OPTIONS, in URL query form (e.g. kinect:joints_s01_e01.txt?frame_offset=190):
//   frame_offset=N     integer: captured frame i takes the track frame with index i + N
//                      (tracks without timestamps; UTKinect numbers frames by image file)
//   time_offset_s=S    seconds: captured time t takes the track frame nearest t + S
//   tolerance_s=S      seconds >= 0: the largest accepted time difference (default 1/60)
//   variant=V          kinect only: utkinect | msr-action3d | msr-daily | utd-mhad |
//                      detect (default)
// See skeleton_track.h for the lookup rule.
//
// Errors: code "usage" for an unknown form (the message lists the accepted ones), an unknown
// or malformed option; otherwise the reader's errors ("not_found", "corrupt",
// "unsupported").

#include <string>

#include "capture-client/skeleton/skeleton_track.h"
#include "common/error/expected.h"

namespace reenact::capture {

Expected<SkeletonTrack> LoadSkeletonTrack(const std::string& spec);

}  // namespace reenact::capture
