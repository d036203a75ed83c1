#pragma once
// UTD-MHAD as ../shared/data/utd-mhad holds it (../shared/data/README.md): one folder per
// sequence, aA_sS_tT (action A 1-27, subject S, trial T), each with depth/NNNNNN.png (320x240,
// millimetres, mirrored as the Kinect SDK delivers them), camera.json and skeleton.txt (the
// Kinect SDK's 20 joints per frame). For `reenact-eval tracker --dataset utd-mhad:ROOT`
// (kinect_reference_eval.h).
//
// The depth is read with rgbd:DIR?mirrored=1 (the true camera's view, where the skeletons'
// sensor frame lies) and the skeletons with kinect:FILE?variant=utd-mhad (16 joints, sensor
// frame: capture-client/skeleton/kinect_v1_skeleton.h).

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/error/expected.h"
#include "tests/eval/reference_agreement.h"

namespace reenact::eval {

struct UtdMhadSequence {
  std::string name;  // the folder's name, e.g. "a14_s3_t1"
  int action = 0, subject = 0, trial = 0;
  std::string dir;  // the folder
};

// "aA_sS_tT" with whole numbers A, S, T >= 1 (no sign, no leading zero), A <= 27; nullopt
// for anything else.
std::optional<UtdMhadSequence> ParseUtdMhadName(std::string_view folder_name);

// The action's name as the data set lists it ("right arm swipe to the left", ...), for
// actions 1-27; "" otherwise.
std::string_view UtdMhadActionName(int action);

// The sequence folders under root, ordered by action, subject and trial. Errors: "not_found"
// when root is not a folder, "usage" when it holds no aA_sS_tT folder.
Expected<std::vector<UtdMhadSequence>> ListUtdMhad(const std::string& root);

// The sources of one sequence (see the header).
std::string UtdMhadDepthSpec(const UtdMhadSequence& sequence);
std::string UtdMhadSkeletonSpec(const UtdMhadSequence& sequence);
std::string UtdMhadSkeletonPath(const UtdMhadSequence& sequence);

// skeleton.txt's 20 joints of every frame, in the file's joint order and coordinates (Kinect
// skeleton space, metres; a joint at (0, 0, 0) is not given), for the baseline over the
// Kinect's own joints: kUtdMhadHipCentre is its hip_center. Errors: "not_found" / "io" when
// the file cannot be read, "corrupt" (naming the file) for a token that is not a finite
// number or a count of numbers that is not a multiple of 60.
inline constexpr int kUtdMhadHipCentre = 3;
Expected<std::vector<std::optional<JointPoints>>> ReadUtdMhadJoints20(const std::string& path);

}  // namespace reenact::eval
