#pragma once
// Choice of the representative frame n^ for model building (thesis Eq. 2-4):
//   F(n) = theta^L_n l^L_n + theta^R_n l^R_n + lambda g(phi^R_n, phi^L_n)        (Eq. 2)
//   n^ = argmax_n F(n)                                                          (Eq. 4)
// on skeletons in each frame's own sensor frame (OpenCV axes: x right in the image).
// - theta^{L,R}: angle in degrees between the torso (neck -> waist) and the arm
//   (shoulder -> hand): 0 with arms hanging, 90 with arms held out.
// - l^{L,R}: |x component| of the unit arm vector: 1 when the arm is parallel to the image
//   rows, so the arm's width shows in the image.
// - g (Eq. 3): 1 when the legs are uncrossed, else 0. The thesis compares two leg angles of a
//   figure we do not have; we implement the intent: the left knee and the left foot each lie
//   on the left-hip side of their right counterparts along the hip axis (r_hip -> l_hip).
// lambda (default 2000, as in the thesis) exceeds the largest arm score (2 * 180), so
// uncrossed legs take precedence.

#include <optional>
#include <span>

#include "common/skeleton/skeleton.h"

namespace reenact {

struct RepresentativeFrameOptions {
  double lambda = 2000.0;  // weight of the legs-uncrossed term, >= 0

  void Check() const;
};

// F(n) of one skeleton (sensor frame); nullopt if a joint the score needs is missing or a
// vector it uses has zero length.
std::optional<double> RepresentativeScore(const Skeleton& skeleton_in_sensor,
                                          const RepresentativeFrameOptions& options = {});

// argmax_n F(n) over the frames that can be scored; ties go to the earliest frame; nullopt if
// none can be scored. usable (if not empty) marks the frames that may be chosen.
std::optional<int> SelectRepresentativeFrame(std::span<const Skeleton> skeletons_in_sensor,
                                             std::span<const bool> usable = {},
                                             const RepresentativeFrameOptions& options = {});

}  // namespace reenact
