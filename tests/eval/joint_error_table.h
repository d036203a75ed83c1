#pragma once
// Per-joint error of a tracked skeleton against ground truth, split into a constant offset
// (bias) and what varies around it (spread), for `reenact-eval tracker`'s "joints" table.
//
// Per frame and joint, the error e = estimate - truth (metres) is expressed in the
// ground-truth body frame of that frame:
//   z  up along the spine: (neck - waist) / |neck - waist|
//   x  the subject's left to its right: (r_shoulder - l_shoulder) + (r_hip - l_hip), made
//      orthogonal to z and normalised
//   y  forward: z x x (right-handed; the way the subject faces)
// Over the frames added:
//   mean_cm   = mean |e|
//   bias      = mean e (the vector, body frame), bias_cm = |bias|
//   spread_cm = sqrt(mean |e - bias|^2)  (the RMS about the bias; so mean |e|^2 = bias^2 +
//               spread^2)
// A frame whose body frame is undefined (a missing neck, waist, shoulder or hip, the neck
// at the waist, or the left-right line along the spine) is left out, and so is any joint
// missing from either skeleton in that frame; `frames` counts what each joint used.

#include <Eigen/Core>
#include <array>
#include <optional>

#include "common/skeleton/skeleton.h"

namespace reenact::eval {

struct JointErrorStats {
  int frames = 0;
  double mean_cm = 0;
  Eigen::Vector3d bias_cm = Eigen::Vector3d::Zero();  // body frame: x right, y forward, z up
  double bias_norm_cm = 0;
  double spread_cm = 0;
};

class JointErrorTable {
 public:
  // Adds one frame; both skeletons in one frame (any). Returns false (and adds nothing) when
  // the truth's body frame is undefined.
  bool Add(const Skeleton& estimate, const Skeleton& truth);
  std::array<JointErrorStats, kJointCount> Stats() const;

 private:
  struct Sum {  // running mean and squared deviations (Welford), metres
    int n = 0;
    double norm = 0;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    double m2 = 0;
  };
  std::array<Sum, kJointCount> sums_{};
};

// The body frame of the header built on any skeleton (columns x, y, z in the skeleton's
// frame), or nothing when it is undefined.
std::optional<Eigen::Matrix3d> BodyFrame(const Skeleton& skeleton);

}  // namespace reenact::eval
