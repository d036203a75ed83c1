#include "tests/eval/limb_visibility_table.h"

#include <algorithm>
#include <cmath>

#include "common/error/check.h"

namespace reenact::eval {
namespace {

struct LimbParts {
  BodyPart upper, lower;
  Joint middle, end;
};
constexpr std::array<LimbParts, kEvalLimbCount> kLimbs = {{
    {BodyPart::kLeftUpperArm, BodyPart::kLeftForearm, Joint::kLeftElbow, Joint::kLeftHand},
    {BodyPart::kRightUpperArm, BodyPart::kRightForearm, Joint::kRightElbow, Joint::kRightHand},
    {BodyPart::kLeftThigh, BodyPart::kLeftShin, Joint::kLeftKnee, Joint::kLeftFoot},
    {BodyPart::kRightThigh, BodyPart::kRightShin, Joint::kRightKnee, Joint::kRightFoot},
}};

double JointError(const Skeleton& estimate, const Skeleton& truth, Joint j) {
  if (!estimate.Has(j) || !truth.Has(j)) return -1;
  const double e = (estimate[j] - truth[j]).norm();
  return std::isfinite(e) ? e : -1;
}

}  // namespace

std::string_view EvalLimbName(int limb) {
  static constexpr std::array<std::string_view, kEvalLimbCount> kNames = {"l_arm", "r_arm", "l_leg",
                                                                          "r_leg"};
  REENACT_CHECK(limb >= 0 && limb < kEvalLimbCount, "limb out of range");
  return kNames[limb];
}

std::array<double, kBodyPartCount> VisiblePartAreas(const ImageLabel8& labels,
                                                    const Skeleton& truth,
                                                    const PinholeCamera& camera) {
  REENACT_CHECK(
      labels.width == camera.width && labels.height == camera.height && labels.channels == 1,
      "part labels must be one channel of the camera's size");
  std::array<long long, kBodyPartCount> count{};
  for (const uint8_t label : labels.data)
    if (label > 0 && label <= kBodyPartCount) ++count[label - 1];
  std::array<double, kBodyPartCount> area{};
  for (int p = 0; p < kBodyPartCount; ++p) {
    const auto [a, b] = PartJoints(static_cast<BodyPart>(p));
    const double z = 0.5 * (truth[a].z() + truth[b].z());
    if (!(z >= kMinPartDepthM) || !std::isfinite(z)) continue;
    area[p] = static_cast<double>(count[p]) * (z / camera.fx) * (z / camera.fy);
  }
  return area;
}

void LimbVisibilityTable::Add(const std::array<double, kBodyPartCount>& part_areas,
                              const Skeleton& estimate, const Skeleton& truth) {
  Frame f;
  for (int l = 0; l < kEvalLimbCount; ++l) {
    const LimbParts& limb = kLimbs[l];
    f.area[l] = part_areas[Index(limb.upper)] + part_areas[Index(limb.lower)];
    f.end_m[l] = JointError(estimate, truth, limb.end);
    f.middle_m[l] = JointError(estimate, truth, limb.middle);
  }
  frames_.push_back(f);
}

std::array<LimbVisibilityStats, kEvalLimbCount> LimbVisibilityTable::Stats() const {
  std::array<LimbVisibilityStats, kEvalLimbCount> out;
  for (int l = 0; l < kEvalLimbCount; ++l) {
    double largest = 0;
    for (const Frame& f : frames_) largest = std::max(largest, f.area[l]);
    int end_n[2] = {}, middle_n[2] = {};
    double end_sum[2] = {}, middle_sum[2] = {};
    LimbVisibilityStats& s = out[l];
    for (const Frame& f : frames_) {
      const int v = largest > 0 && f.area[l] >= kInViewAreaRatio * largest ? 1 : 0;
      ++(v ? s.in_view : s.hidden);
      if (f.end_m[l] >= 0) ++end_n[v], end_sum[v] += f.end_m[l];
      if (f.middle_m[l] >= 0) ++middle_n[v], middle_sum[v] += f.middle_m[l];
    }
    const auto mean_cm = [](double sum, int n) { return n ? 100 * sum / n : 0.0; };
    s.hidden_end_cm = mean_cm(end_sum[0], end_n[0]);
    s.in_view_end_cm = mean_cm(end_sum[1], end_n[1]);
    s.hidden_middle_cm = mean_cm(middle_sum[0], middle_n[0]);
    s.in_view_middle_cm = mean_cm(middle_sum[1], middle_n[1]);
  }
  return out;
}

}  // namespace reenact::eval
