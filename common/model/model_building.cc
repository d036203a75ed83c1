#include "common/model/model_building.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "common/error/check.h"
#include "common/estimate/median.h"

namespace reenact {
namespace {

// Whether the images can go to FitRadiusRatios without breaking its preconditions.
bool ImagesUsable(const ModelFrameImages& im) {
  const PinholeCamera& c = im.camera;
  const Distortion& d = c.distortion;
  const bool camera_ok = c.width > 0 && c.height > 0 && std::isfinite(c.fx) && c.fx > 0 &&
                         std::isfinite(c.fy) && c.fy > 0 && std::isfinite(c.cx) &&
                         std::isfinite(c.cy) && std::isfinite(d.k1) && std::isfinite(d.k2) &&
                         std::isfinite(d.p1) && std::isfinite(d.p2) && std::isfinite(d.k3);
  const auto sized = [&c](const auto& image) {
    return image.width == c.width && image.height == c.height && image.channels == 1 &&
           image.data.size() == static_cast<size_t>(c.width) * c.height;
  };
  return camera_ok && sized(im.depth) && sized(im.mask);
}

// Shorter than kMinBoneLength, or than radius_fit's 2 pixels once projected.
bool ShortBone(const Skeleton& s, BodyPart part, const PinholeCamera& camera) {
  const auto [a, b] = PartJoints(part);
  if (!((s[b] - s[a]).norm() >= kMinBoneLength)) return true;
  const auto pa = camera.Project(s[a]), pb = camera.Project(s[b]);
  return pa && pb && (*pb - *pa).norm() < 2.0;
}

}  // namespace

void ModelBuildOptions::Check() const {
  representative.Check();
  fit.Check();
  REENACT_CHECK(robust_k >= 1, "robust_k must be >= 1");
  REENACT_CHECK(min_part_fits >= 1 && min_part_fits <= robust_k,
                "min_part_fits must lie in [1, robust_k]");
  REENACT_CHECK(std::isfinite(max_ratio) && max_ratio > 0, "max_ratio must be finite and > 0");
  REENACT_CHECK(max_skipped_frames >= 0, "max_skipped_frames must be >= 0");
}

std::string_view PartFitOutcomeName(PartFitOutcome outcome) {
  switch (outcome) {
    case PartFitOutcome::kFitted:
      return "fitted";
    case PartFitOutcome::kNoFrame:
      return "no_frame";
    case PartFitOutcome::kMissingJoint:
      return "missing_joint";
    case PartFitOutcome::kShortBone:
      return "short_bone";
    case PartFitOutcome::kNoPixels:
      return "no_pixels";
    case PartFitOutcome::kTooFewSlices:
      return "too_few_slices";
    case PartFitOutcome::kImplausible:
      return "implausible";
    case PartFitOutcome::kTooFewFits:
      return "too_few_fits";
  }
  return "unknown";
}

int ModelBuildResult::fitted_count() const {
  return static_cast<int>(std::count(fitted.begin(), fitted.end(), true));
}

ModelBuildResult BuildCylinderModel(std::span<const Skeleton> skeletons,
                                    const ModelFrameImagesFn& images,
                                    const ModelBuildOptions& options,
                                    std::span<const bool> usable) {
  options.Check();
  REENACT_CHECK(usable.empty() || usable.size() == skeletons.size(),
                "usable must be empty or one flag per skeleton");
  REENACT_CHECK(static_cast<bool>(images), "an images callback is required");

  // Rank the scorable frames by F(n), highest first, ties to the earlier frame.
  std::vector<std::pair<double, int>> ranked;
  for (size_t n = 0; n < skeletons.size(); ++n) {
    if (!usable.empty() && !usable[n]) continue;
    const std::optional<double> f = RepresentativeScore(skeletons[n], options.representative);
    if (f && std::isfinite(*f)) ranked.emplace_back(*f, static_cast<int>(n));
  }
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });

  ModelBuildResult result;
  result.radius_ratio = DefaultRadiusRatios();
  result.outcome.fill(PartFitOutcome::kNoFrame);
  std::array<std::vector<double>, kBodyPartCount> kept;
  std::array<std::optional<PartFitOutcome>, kBodyPartCount> first_failure;

  for (const auto& [score, n] : ranked) {
    if (static_cast<int>(result.fitted_frames.size()) >= options.robust_k) break;
    if (static_cast<int>(result.skipped_frames.size()) > options.max_skipped_frames) break;
    std::optional<ModelFrameImages> im = images(n);
    if (!im || !ImagesUsable(*im)) {
      result.skipped_frames.push_back(n);
      continue;
    }
    const Skeleton& s = skeletons[n];
    const RadiusFitResult fit = FitRadiusRatios(s, im->camera, im->depth, im->mask, options.fit);
    const bool first_frame = result.fitted_frames.empty();
    result.fitted_frames.push_back(n);
    result.frame_scores.push_back(score);
    for (int p = 0; p < kBodyPartCount; ++p) {
      const auto part = static_cast<BodyPart>(p);
      const double ratio = fit.radius_ratio[p];
      PartFitOutcome why = PartFitOutcome::kFitted;
      if (!s.HasPart(part)) {
        why = PartFitOutcome::kMissingJoint;
      } else if (ShortBone(s, part, im->camera)) {
        why = PartFitOutcome::kShortBone;
      } else if (!fit.fitted[p]) {
        why = fit.pixel_count[p] == 0 ? PartFitOutcome::kNoPixels : PartFitOutcome::kTooFewSlices;
      } else if (!(std::isfinite(ratio) && ratio > 0 && ratio <= options.max_ratio)) {
        why = PartFitOutcome::kImplausible;
      }
      if (why == PartFitOutcome::kFitted)
        kept[p].push_back(ratio);
      else if (first_frame)
        first_failure[p] = why;
    }
  }

  if (!result.fitted_frames.empty()) result.representative_frame = result.fitted_frames.front();
  for (int p = 0; p < kBodyPartCount; ++p) {
    result.fit_count[p] = static_cast<int>(kept[p].size());
    if (result.fitted_frames.empty()) continue;
    if (result.fit_count[p] >= options.min_part_fits) {
      result.radius_ratio[p] = Median(kept[p]);
      result.fitted[p] = true;
      result.outcome[p] = PartFitOutcome::kFitted;
    } else if (result.fit_count[p] > 0) {
      result.outcome[p] = PartFitOutcome::kTooFewFits;
    } else {
      result.outcome[p] = first_failure[p].value_or(PartFitOutcome::kTooFewSlices);
    }
  }
  return result;
}

}  // namespace reenact
