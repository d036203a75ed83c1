#include "capture-client/tracker/body_start.h"

#include "capture-client/tracker/extremity_pose.h"
#include "capture-client/tracker/heading.h"
#include "common/error/check.h"

namespace reenact::capture {

void BodyStartOptions::Check() const {
  REENACT_CHECK(heading_candidates >= 1, "heading_candidates must be >= 1");
  extremities.Check();
  REENACT_CHECK(extremity_min_offset_m >= 0, "extremity_min_offset_m must be >= 0");
  REENACT_CHECK(facing_sensor_gain >= 0 && facing_sensor_gain < 1,
                "facing_sensor_gain must be in [0, 1)");
  REENACT_CHECK(restart_taller_m > 0 && restart_taller_frames >= 1,
                "restart_taller_m must be > 0 and restart_taller_frames >= 1");
}

double PosedTopHeight(const ArticulatedBody& body, const Skeleton& posed, const Plane3& floor) {
  const BodyShape& shape = body.shape();
  const double crown = shape.StandingHeight() - shape.RestSkeleton()[Joint::kHead].z();
  double top = floor.SignedDistance(posed[Joint::kHead]) + crown;
  for (const Eigen::Vector3d& p : posed.position) top = std::max(top, floor.SignedDistance(p));
  return top;
}

std::optional<BodyFitResult> BestUprightFit(const BodyFitter& fitter, const PersonBlob& blob,
                                            const BodyObservation& obs,
                                            const std::vector<Eigen::Vector3d>& headings,
                                            const GeodesicExtremities* extremities,
                                            double extremity_min_offset_m,
                                            double facing_sensor_gain, bool* from_extremities) {
  *from_extremities = false;
  if (!blob.floor_in_sensor) return std::nullopt;
  const Eigen::Vector3d up = blob.floor_in_sensor->normal;
  const Eigen::Vector3d ground =
      blob.centroid - blob.floor_in_sensor->SignedDistance(blob.centroid) * up;
  const auto weighed = [&](const BodyFitResult& r) {
    const bool away = FacesAwayFrom(r.pose, up, Eigen::Vector3d::Zero());
    return away ? r.cost / (1 - facing_sensor_gain) : r.cost;
  };
  std::optional<BodyFitResult> best;
  for (const Eigen::Vector3d& forward : headings) {
    const ArticulatedPose start = UprightPose(fitter.body(), ground, up, forward);
    BodyFitResult r = fitter.FitFromFar(start, obs);
    if (!best || weighed(r) < weighed(*best)) {
      best = std::move(r);
      *from_extremities = false;
    }
    if (!extremities) continue;
    int placed = 0;
    const ArticulatedPose reach =
        PoseFromExtremities(fitter.body(), start, *extremities, fitter.options().limits, &placed,
                            extremity_min_offset_m);
    if (placed == 0) continue;
    BodyFitResult e = fitter.FitFromFar(reach, obs);
    if (weighed(e) < weighed(*best)) {
      best = std::move(e);
      *from_extremities = true;
    }
  }
  return best;
}

std::optional<StartedFit> StartTrack(const BodyFitter& fitter, const GoodFitCriteria& good,
                                     const PersonBlob& blob, const BodyObservation& obs,
                                     const CalibrationOptions& calibration,
                                     const BodyStartOptions& options,
                                     const std::optional<ArticulatedPose>& last_pose,
                                     bool with_extremities) {
  const CalibrationPoseTest test = TestCalibrationPose(blob, calibration);
  if (auto start = CalibrationStartPose(fitter.body(), blob, test)) {
    BodyFitResult r = fitter.LocalFitFromFar(*start, obs);
    if (good.Good(r)) return StartedFit{std::move(r), TrackStart::kCalibrationPose};
  }
  if (!options.from_silhouette || !blob.floor_in_sensor) return std::nullopt;
  const Eigen::Vector3d up = blob.floor_in_sensor->normal;
  std::vector<Eigen::Vector3d> headings =
      CandidateHeadings(up, -blob.centroid, options.heading_candidates);
  if (headings.empty()) return std::nullopt;
  if (last_pose)
    if (auto f = HorizontalForward(*last_pose, up)) headings.push_back(*f);
  std::optional<GeodesicExtremities> extremities;
  if (options.from_extremities && with_extremities)
    extremities = FindGeodesicExtremities(blob.points, blob.floor_in_sensor, options.extremities);
  bool from_extremities = false;
  std::optional<BodyFitResult> best =
      BestUprightFit(fitter, blob, obs, headings, extremities ? &*extremities : nullptr,
                     options.extremity_min_offset_m, options.facing_sensor_gain, &from_extremities);
  if (!best || !good.Good(*best)) return std::nullopt;
  return StartedFit{std::move(*best), TrackStart::kSilhouette, from_extremities};
}

}  // namespace reenact::capture
