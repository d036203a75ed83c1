#pragma once
// Limb error by whether the depth frame shows the limb, for `reenact-eval tracker`'s "limbs"
// table: is a hand (foot) that the tracker places far off one the frame shows, or one hidden
// by the body or beyond the image's edge? A hidden limb's place is a guess whatever the
// tracker does; a limb in view that is far off is the tracker's to mend.
//
// A part's visible area on a frame (VisiblePartAreas): its pixels in the ground-truth part
// labels, each counted as the area it covers at the part's depth, (z / fx) (z / fy) square
// metres, z the sensor-frame depth of the part's middle (the midpoint of its two joints); 0
// for a part whose middle lies less than kMinPartDepthM ahead of the sensor. A limb's visible
// area is that of its two parts (upper arm and forearm, thigh and shin). Over the frames added,
// a frame shows the limb in view when its visible area is at least kInViewAreaRatio of the
// largest the limb showed on any of them (a limb seen broadside shows about its length times
// its width, one behind the body little or nothing); a limb never seen is hidden on every
// frame.
// Per limb: the frames in view and hidden, and over each the mean error of the limb's end
// joint (hand, foot) and of its middle joint (elbow, knee), cm; 0 where there are no such
// frames. Only joints present in both skeletons count.

#include <array>
#include <string_view>
#include <vector>

#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "common/skeleton/skeleton.h"

namespace reenact::eval {

inline constexpr int kEvalLimbCount = 4;  // left arm, right arm, left leg, right leg
inline constexpr double kInViewAreaRatio = 0.25;
inline constexpr double kMinPartDepthM = 0.05;

// "l_arm", "r_arm", "l_leg", "r_leg"; CHECK: 0 <= limb < kEvalLimbCount.
std::string_view EvalLimbName(int limb);

// Visible area of each body part (Index(BodyPart)), square metres. labels: the ground-truth
// part labels (PartLabel, 0 background) of a frame of `camera` (its size: CHECK); truth: the
// ground-truth skeleton in the sensor frame.
std::array<double, kBodyPartCount> VisiblePartAreas(const ImageLabel8& labels,
                                                    const Skeleton& truth,
                                                    const PinholeCamera& camera);

struct LimbVisibilityStats {
  int in_view = 0, hidden = 0;  // frames
  double in_view_end_cm = 0, hidden_end_cm = 0;
  double in_view_middle_cm = 0, hidden_middle_cm = 0;
};

class LimbVisibilityTable {
 public:
  // Adds one tracked frame: the parts' visible areas (VisiblePartAreas), the estimate and the
  // truth (one frame, any).
  void Add(const std::array<double, kBodyPartCount>& part_areas, const Skeleton& estimate,
           const Skeleton& truth);
  std::array<LimbVisibilityStats, kEvalLimbCount> Stats() const;

 private:
  struct Frame {
    std::array<double, kEvalLimbCount> area{};
    // Errors in metres; negative where a joint is missing from either skeleton.
    std::array<double, kEvalLimbCount> end_m{}, middle_m{};
  };
  std::vector<Frame> frames_;
};

}  // namespace reenact::eval
