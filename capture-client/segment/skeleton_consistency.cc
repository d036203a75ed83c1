#include "capture-client/segment/skeleton_consistency.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "common/error/check.h"
#include "common/estimate/median.h"

namespace reenact::capture {
namespace {

bool Usable(const Skeleton& s, Joint j) { return s.Has(j) && s[j].allFinite(); }

std::string Format(const char* format, double a, double b, double c) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, format, a, b, c);
  return buffer;
}

// Flags the minority side of every chain of frames linked by axis comparisons.
void CheckAxis(const std::vector<Skeleton>& skeletons, Joint left, Joint right, const char* what,
               const SkeletonConsistencyOptions& options, std::vector<FrameConsistency>* frames) {
  const double min_cosine = std::cos(options.max_axis_turn_deg * std::numbers::pi / 180);
  struct Sample {
    int frame;
    Eigen::Vector3d axis;
    bool flipped;
    double turn_deg;  // against the previous sample of the chain
  };
  std::vector<std::vector<Sample>> chains;
  for (int f = 0; f < static_cast<int>(skeletons.size()); ++f) {
    const Skeleton& s = skeletons[f];
    if (!Usable(s, left) || !Usable(s, right)) continue;
    const Eigen::Vector3d axis = s[left] - s[right];
    if (!(axis.norm() > 1e-6)) continue;
    const Eigen::Vector3d unit = axis.normalized();
    if (chains.empty() || f - chains.back().back().frame > options.max_gap_frames) {
      chains.push_back({{f, unit, false, 0}});
      continue;
    }
    const Sample& previous = chains.back().back();
    const double cosine = std::clamp(unit.dot(previous.axis), -1.0, 1.0);
    chains.back().push_back({f, unit, previous.flipped != (cosine < min_cosine),
                             std::acos(cosine) * 180 / std::numbers::pi});
  }
  for (const auto& chain : chains) {
    const auto flipped =
        std::count_if(chain.begin(), chain.end(), [](const Sample& s) { return s.flipped; });
    const auto upright = static_cast<long>(chain.size()) - flipped;
    if (flipped == upright) continue;
    const bool wrong_side = flipped < upright;
    for (size_t i = 0; i < chain.size(); ++i) {
      if (chain[i].flipped != wrong_side) continue;
      // The larger turn against a neighbour in the chain, for the message.
      double turn = chain[i].turn_deg;
      if (i + 1 < chain.size()) turn = std::max(turn, chain[i + 1].turn_deg);
      FrameConsistency& fc = (*frames)[chain[i].frame];
      fc.flags.push_back(
          {SkeletonIssue::kLeftRightSwap, -1, 0, 0,
           std::string("left and right swapped (") + what + "): the axis turns " +
               Format("%.0f degrees against its neighbours, while %.0f of %.0f linked frames "
                      "keep the other side",
                      turn, static_cast<double>(std::max(flipped, upright)),
                      static_cast<double>(chain.size()))});
    }
  }
}

}  // namespace

void SkeletonConsistencyOptions::Check() const {
  REENACT_CHECK(max_relative_deviation > 0 && max_relative_deviation <= 1,
                "max_relative_deviation must lie in (0, 1]");
  REENACT_CHECK(std::isfinite(min_absolute_deviation_m) && min_absolute_deviation_m >= 0,
                "min_absolute_deviation_m must be >= 0");
  REENACT_CHECK(max_axis_turn_deg > 0 && max_axis_turn_deg < 180,
                "max_axis_turn_deg must lie in (0, 180)");
  REENACT_CHECK(max_gap_frames >= 1, "max_gap_frames must be >= 1");
}

std::string_view SkeletonIssueName(SkeletonIssue issue) {
  switch (issue) {
    case SkeletonIssue::kMissingJoints:
      return "missing_joints";
    case SkeletonIssue::kBoneLength:
      return "bone_length";
    case SkeletonIssue::kLeftRightSwap:
      return "left_right_swap";
  }
  return "unknown";
}

SkeletonConsistency CheckSkeletonConsistency(const std::vector<Skeleton>& skeletons,
                                             const SkeletonConsistencyOptions& options) {
  options.Check();
  SkeletonConsistency out;
  const int n = static_cast<int>(skeletons.size());
  out.frames.resize(n);
  const auto& bones = SkeletonBones();

  for (int f = 0; f < n; ++f) {
    std::string missing;
    for (int j = 0; j < kJointCount; ++j)
      if (!Usable(skeletons[f], static_cast<Joint>(j)))
        missing += (missing.empty() ? "" : ", ") + std::string(JointName(static_cast<Joint>(j)));
    if (!missing.empty())
      out.frames[f].flags.push_back(
          {SkeletonIssue::kMissingJoints, -1, 0, 0, "missing joints: " + missing});
  }

  std::vector<std::array<double, kBoneCount>> lengths(n);
  for (int b = 0; b < kBoneCount; ++b) {
    std::vector<double> present;
    for (int f = 0; f < n; ++f) {
      const Skeleton& s = skeletons[f];
      lengths[f][b] = -1;
      if (!Usable(s, bones[b].a) || !Usable(s, bones[b].b)) continue;
      lengths[f][b] = (s[bones[b].b] - s[bones[b].a]).norm();
      present.push_back(lengths[f][b]);
    }
    if (present.empty()) continue;
    const double median = Median(std::move(present));
    out.median_length_m[b] = median;
    const double tolerance =
        std::max(options.max_relative_deviation * median, options.min_absolute_deviation_m);
    for (int f = 0; f < n; ++f) {
      const double length = lengths[f][b];
      if (length < 0 || std::abs(length - median) <= tolerance) continue;
      const double percent = median > 0 ? 100 * (length - median) / median : 0;
      out.frames[f].flags.push_back(
          {SkeletonIssue::kBoneLength, b, length, median,
           std::string(bones[b].name) +
               Format(" %.3f m, clip median %.3f m (%+.0f%%)", length, median, percent)});
    }
  }

  if (options.check_left_right) {
    CheckAxis(skeletons, Joint::kLeftShoulder, Joint::kRightShoulder, "shoulders", options,
              &out.frames);
    CheckAxis(skeletons, Joint::kLeftHip, Joint::kRightHip, "hips", options, &out.frames);
  }
  for (FrameConsistency& fc : out.frames) {
    fc.usable = fc.flags.empty();
    out.usable_frames += fc.usable;
  }
  return out;
}

}  // namespace reenact::capture
