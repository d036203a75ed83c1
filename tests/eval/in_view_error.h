#pragma once
// A tracked skeleton's error split by what the sensor shows, for a subject partly out of view
// (`reenact-eval tracker`'s in_view_mpjpe_cm, in_view_reported and invented).
//
// A ground-truth joint (sensor frame, OpenCV: z forward, metres) is in view when it is present,
// lies more than 5 cm in front of the sensor (z > 0.05) and projects inside the image: pixel
// coordinates in [0, width) x [0, height) of the camera (distortion applied, as
// PinholeCamera::Project does). A tracked joint is reported when its confidence is above 0
// (skeleton.h: confidence 0 is "not seen").
// Over the frames added (each a frame that gave a skeleton):
//   in_view_mpjpe_cm   the mean, over the frames with at least one in-view joint the tracker
//                      reported, of that frame's mean error over those joints (cm): the 16-joint
//                      MPJPE of a frame that shows and reports every joint
//   in_view_reported   reported in-view joints / in-view joints, all frames pooled
//   invented           reported out-of-view joints / out-of-view joints, all frames pooled: the
//                      joints the tracker placed without seeing them (they should be flagged
//                      not seen, confidence 0)
// Each is 0 where nothing counts towards it (no frame, no in-view or no out-of-view joint).

#include <array>

#include "common/geometry/pinhole_camera.h"
#include "common/skeleton/skeleton.h"

namespace reenact::eval {

// Which joints of the truth (sensor frame) are in view of `camera` (see above).
std::array<bool, kJointCount> JointsInView(const Skeleton& truth_in_sensor,
                                           const PinholeCamera& camera);

struct InViewErrorStats {
  int frames = 0;                                 // frames added
  int in_view = 0, in_view_reported = 0;          // joint counts, all frames
  int out_of_view = 0, out_of_view_reported = 0;  // joint counts, all frames
  double in_view_mpjpe_cm = 0;
  double in_view_reported_share = 0;  // in_view_reported / in_view
  double invented_share = 0;          // out_of_view_reported / out_of_view
};

class InViewErrorTable {
 public:
  // Adds one tracked frame: the tracker's skeleton and the truth, both in the sensor frame.
  void Add(const Skeleton& estimate, const Skeleton& truth_in_sensor, const PinholeCamera& camera);
  InViewErrorStats Stats() const;

 private:
  InViewErrorStats sums_;
  int error_frames_ = 0;        // frames with an in-view, reported joint
  double frame_error_sum_ = 0;  // sum of those frames' mean errors, metres
};

}  // namespace reenact::eval
