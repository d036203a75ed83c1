#include "tests/eval/in_view_error.h"

namespace reenact::eval {

std::array<bool, kJointCount> JointsInView(const Skeleton& truth, const PinholeCamera& camera) {
  std::array<bool, kJointCount> in_view{};
  for (int j = 0; j < kJointCount; ++j) {
    if (!truth.Has(static_cast<Joint>(j))) continue;
    const auto uv = camera.Project(truth.position[j], 0.05);
    in_view[j] =
        uv && uv->x() >= 0 && uv->y() >= 0 && uv->x() < camera.width && uv->y() < camera.height;
  }
  return in_view;
}

void InViewErrorTable::Add(const Skeleton& estimate, const Skeleton& truth,
                           const PinholeCamera& camera) {
  const std::array<bool, kJointCount> in_view = JointsInView(truth, camera);
  ++sums_.frames;
  int n = 0;
  double sum = 0;
  for (int j = 0; j < kJointCount; ++j) {
    const Joint joint = static_cast<Joint>(j);
    if (!truth.Has(joint)) continue;
    const bool reported = estimate.Has(joint);
    if (!in_view[j]) {
      ++sums_.out_of_view;
      sums_.out_of_view_reported += reported;
      continue;
    }
    ++sums_.in_view;
    if (!reported) continue;
    ++sums_.in_view_reported;
    ++n;
    sum += (estimate[joint] - truth[joint]).norm();
  }
  if (n > 0) {
    ++error_frames_;
    frame_error_sum_ += sum / n;
  }
}

InViewErrorStats InViewErrorTable::Stats() const {
  InViewErrorStats s = sums_;
  if (error_frames_ > 0) s.in_view_mpjpe_cm = 100 * frame_error_sum_ / error_frames_;
  if (s.in_view > 0) s.in_view_reported_share = static_cast<double>(s.in_view_reported) / s.in_view;
  if (s.out_of_view > 0)
    s.invented_share = static_cast<double>(s.out_of_view_reported) / s.out_of_view;
  return s;
}

}  // namespace reenact::eval
