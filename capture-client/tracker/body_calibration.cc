#include "capture-client/tracker/body_calibration.h"

#include <algorithm>
#include <cmath>

#include "capture-client/tracker/torso_depth.h"
#include "common/error/check.h"
#include "common/estimate/median.h"

namespace reenact::capture {

void CalibrationOptions::Check() const {
  REENACT_CHECK(min_height_m > 0 && min_height_m < max_height_m,
                "need 0 < min_height < max_height");
  REENACT_CHECK(min_span_ratio > 0 && max_offset_ratio > 0, "ratios must be > 0");
  REENACT_CHECK(refine_rounds >= 0, "refine_rounds must be >= 0");
  REENACT_CHECK(average_neck_depth_ratio > 0 && head_scale_noise >= 0 && min_head_scale > 0 &&
                    min_head_scale <= 1 && max_head_scale >= 1,
                "need average_neck_depth_ratio > 0, head_scale_noise >= 0 and "
                "0 < min_head_scale <= 1 <= max_head_scale");
  fit.Check();
  shape.Check();
}

std::string_view CalibrationStatusName(CalibrationStatus status) {
  switch (status) {
    case CalibrationStatus::kOk:
      return "ok";
    case CalibrationStatus::kNoPerson:
      return "no_person";
    case CalibrationStatus::kImplausibleHeight:
      return "implausible_height";
    case CalibrationStatus::kNotCalibrationPose:
      return "not_calibration_pose";
  }
  return "unknown";
}

CalibrationPoseTest TestCalibrationPose(const PersonBlob& blob, const CalibrationOptions& o) {
  CalibrationPoseTest t;
  if (blob.status != DetectStatus::kOk || !blob.floor_in_sensor || blob.points.empty()) return t;
  const Plane3& floor = *blob.floor_in_sensor;
  const Eigen::Vector3d up = floor.normal;
  Eigen::Vector3d forward = -blob.centroid;
  forward -= forward.dot(up) * up;
  if (forward.norm() < 1e-6) return t;
  forward.normalize();
  const Eigen::Vector3d left = up.cross(forward);
  t.sensor_from_body.col(0) = forward;
  t.sensor_from_body.col(1) = left;
  t.sensor_from_body.col(2) = up;
  t.floor_origin = blob.centroid - floor.SignedDistance(blob.centroid) * up;
  t.height_m = blob.top_height_m;
  if (t.height_m < o.min_height_m || t.height_m > o.max_height_m) {
    t.status = CalibrationStatus::kImplausibleHeight;
    return t;
  }
  const double h = t.height_m;
  double lo = 1e9, hi = -1e9;
  std::vector<double> legs;
  for (const Eigen::Vector3d& p : blob.points) {
    const double z = floor.SignedDistance(p), l = (p - t.floor_origin).dot(left);
    if (z >= 0.6 * h && z <= 0.95 * h) lo = std::min(lo, l), hi = std::max(hi, l);
    if (z >= 0.3 * h && z <= 0.5 * h) legs.push_back(l);
  }
  t.span_m = hi > lo ? hi - lo : 0;
  t.centre_lateral_m = legs.empty() ? 0 : Median(legs);
  const bool arms_out = !legs.empty() && t.span_m >= o.min_span_ratio * h &&
                        std::abs(0.5 * (hi + lo) - t.centre_lateral_m) <= o.max_offset_ratio * h;
  t.status = arms_out ? CalibrationStatus::kOk : CalibrationStatus::kNotCalibrationPose;
  return t;
}

std::optional<ArticulatedPose> CalibrationStartPose(const ArticulatedBody& body,
                                                    const PersonBlob& blob,
                                                    const CalibrationPoseTest& test) {
  if (test.status != CalibrationStatus::kOk) return std::nullopt;
  const BodyShape& s = body.shape();
  Skeleton target = s.RestSkeleton();  // body frame, feet on z = 0
  for (const auto& [sh, el, ha, side] :
       {std::tuple{Joint::kLeftShoulder, Joint::kLeftElbow, Joint::kLeftHand, 1.0},
        std::tuple{Joint::kRightShoulder, Joint::kRightElbow, Joint::kRightHand, -1.0}}) {
    target[el] = target[sh] + Eigen::Vector3d(0, side * s.upper_arm, 0);
    target[ha] = target[el] + Eigen::Vector3d(0, side * s.forearm, 0);
  }
  // Depth of the torso's front surface along forward (towards the sensor).
  const Eigen::Vector3d forward = test.sensor_from_body.col(0);
  const Eigen::Vector3d left = test.sensor_from_body.col(1);
  const Eigen::Vector3d up = test.sensor_from_body.col(2);
  const double h = test.height_m;
  std::vector<double> front;
  for (const Eigen::Vector3d& p : blob.points) {
    const Eigen::Vector3d d = p - test.floor_origin;
    if (d.dot(up) >= 0.6 * h && d.dot(up) <= 0.75 * h &&
        std::abs(d.dot(left) - test.centre_lateral_m) < 0.08 * h)
      front.push_back(d.dot(forward));
  }
  const double front_m = front.empty() ? 0 : Median(front);
  Eigen::Isometry3d sensor_from_body = Eigen::Isometry3d::Identity();
  sensor_from_body.linear() = test.sensor_from_body;
  sensor_from_body.translation() =
      test.floor_origin + left * test.centre_lateral_m + forward * (front_m - s.torso_radius);
  return body.PoseFromSkeleton(target.Transformed(sensor_from_body));
}

namespace {

// Median distance of the points nearest to each capsule kind to its axis (middle 70%).
void RefitRadii(const ArticulatedBody& body, const PosedBody3& posed,
                const std::vector<Eigen::Vector3d>& points, double outlier_m, BodyShape* shape,
                const BodyShape& prior) {
  const auto& caps = body.capsules();
  std::vector<std::vector<double>> dist(caps.size());
  for (const Eigen::Vector3d& p : points) {
    double best = 1e9, best_axis = 0, best_t = 0;
    int bi = -1;
    for (size_t k = 0; k < caps.size(); ++k) {
      const Eigen::Isometry3d& t = posed.sensor_from_segment[static_cast<int>(caps[k].segment)];
      const Eigen::Vector3d a = t * caps[k].a, ab = t * caps[k].b - a;
      const double tt = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-12), 0.0, 1.0);
      const double d = (p - a - tt * ab).norm();
      if (d - caps[k].radius < best)
        best = d - caps[k].radius, bi = static_cast<int>(k), best_axis = d, best_t = tt;
    }
    if (bi >= 0 && std::abs(best) <= outlier_m && best_t >= 0.15 && best_t <= 0.85)
      dist[bi].push_back(best_axis);
  }
  auto refit = [&](std::initializer_list<int> ks, double* radius, double prior_radius) {
    std::vector<double> all;
    for (int k : ks) all.insert(all.end(), dist[k].begin(), dist[k].end());
    if (all.size() < 10) return;
    *radius = std::clamp(Median(all), 0.6 * prior_radius, 1.5 * prior_radius);
  };
  // Capsule order of BodyShape::Capsules(): head, then (chest, lower spine, pelvis) per side,
  // upper arms, forearms, thighs, then (shin, foot) per side.
  refit({0}, &shape->head_radius, prior.head_radius);
  refit({1, 2, 4, 5}, &shape->torso_radius, prior.torso_radius);
  refit({7, 8}, &shape->upper_arm_radius, prior.upper_arm_radius);
  refit({9, 10}, &shape->forearm_radius, prior.forearm_radius);
  refit({11, 12}, &shape->thigh_radius, prior.thigh_radius);
  refit({13, 15}, &shape->shin_radius, prior.shin_radius);
}

// The trunk's half breadth measured on the calibration frame (MeasureTrunkBreadth), within
// [0.6, 1.5] of the prior's; unchanged where the abdomen shows too little.
void RefitTrunkBreadth(const ArticulatedBody& body, const PosedBody3& posed, const PersonBlob& blob,
                       const PinholeCamera& camera, BodyShape* shape, const BodyShape& prior) {
  const std::optional<double> half_breadth = MeasureTrunkBreadth(body, posed, blob, camera);
  if (!half_breadth) return;
  const double prior_half_breadth = prior.torso_radius + prior.torso_half_spread;
  *shape = WithTorsoBreadth(
      *shape, std::clamp(*half_breadth, 0.6 * prior_half_breadth, 1.5 * prior_half_breadth));
}

// `scaled` with its two spine lengths scaled together to give `original`'s standing height.
BodyShape SpineKeepingHeight(BodyShape scaled, const BodyShape& original) {
  const double spine = scaled.lower_spine + scaled.upper_spine;
  const double k = (spine + original.StandingHeight() - scaled.StandingHeight()) / spine;
  scaled.lower_spine *= k;
  scaled.upper_spine *= k;
  return scaled;
}

}  // namespace

BodyShape WithHeadScaled(const BodyShape& shape, double scale) {
  REENACT_CHECK(scale > 0 && std::isfinite(scale), "head scale must be positive");
  BodyShape s = shape;
  s.head_radius *= scale;
  s.head_rise *= scale;
  return SpineKeepingHeight(s, shape);
}

BodyShape WithLegsScaled(const BodyShape& shape, double scale) {
  REENACT_CHECK(scale > 0 && std::isfinite(scale), "leg scale must be positive");
  BodyShape s = shape;
  s.thigh *= scale;
  s.shin *= scale;
  return SpineKeepingHeight(s, shape);
}

double ScaleBeyondNoise(double m, double noise, double lo, double hi) {
  REENACT_CHECK(m > 0 && std::isfinite(m), "measured ratio must be positive");
  REENACT_CHECK(noise >= 0 && lo > 0 && lo <= hi, "need noise >= 0, 0 < lo <= hi");
  const double excess = std::max(0.0, std::abs(m - 1) - noise);
  return std::clamp(1 + std::copysign(excess, m - 1), lo, hi);
}

BodyCalibration ProportionalBody(const PersonBlob& blob, const CalibrationOptions& options,
                                 std::optional<double> neck_below_top_m) {
  options.Check();
  BodyCalibration c;
  c.from_calibration_pose = false;
  if (blob.status != DetectStatus::kOk || blob.points.empty()) return c;
  c.height_m = blob.top_height_m;
  if (c.height_m < options.min_height_m || c.height_m > options.max_height_m) {
    c.status = CalibrationStatus::kImplausibleHeight;
    return c;
  }
  c.status = CalibrationStatus::kOk;
  c.shape = BodyShape::FromHeight(c.height_m);
  if (neck_below_top_m) {
    REENACT_CHECK(*neck_below_top_m > 0 && std::isfinite(*neck_below_top_m),
                  "neck depth must be positive");
    c.shape = WithHeadScaled(
        c.shape,
        ScaleBeyondNoise(*neck_below_top_m / (options.average_neck_depth_ratio * c.height_m),
                         options.head_scale_noise, options.min_head_scale, options.max_head_scale));
  }
  const auto lengths = c.shape.PartLengths();
  const auto radii = c.shape.PartRadii();
  for (int i = 0; i < kBodyPartCount; ++i) c.radius_ratio[i] = radii[i] / lengths[i];
  return c;
}

BodyCalibration CalibrateBody(const PersonBlob& blob, const PinholeCamera& camera, int subsample,
                              const CalibrationOptions& options) {
  options.Check();
  BodyCalibration c;
  const CalibrationPoseTest test = TestCalibrationPose(blob, options);
  c.status = test.status;
  c.height_m = test.height_m;
  c.span_m = test.span_m;
  if (test.status != CalibrationStatus::kOk) return c;
  const double h = test.height_m;
  BodyShape shape = BodyShape::FromHeight(h);
  const double arm = shape.upper_arm + shape.forearm;
  const double scale =
      std::clamp((0.5 * test.span_m - shape.shoulder_half_width - 0.062 * h) / arm, 0.8, 1.25);
  shape.upper_arm *= scale;
  shape.forearm *= scale;
  const BodyShape prior = shape;
  const BodyObservation obs = MakeObservation(camera, blob.grid_step_px, blob.mask, blob.depth_m,
                                              blob.points, blob.pixels, subsample);
  ArticulatedPose pose = *CalibrationStartPose(ArticulatedBody(shape), blob, test);
  for (int round = 0; round <= options.refine_rounds; ++round) {
    const ArticulatedBody body(shape);
    c.fit = FitBody(body, pose, obs, options.fit);
    pose = c.fit.pose;
    if (round == options.refine_rounds) break;
    RefitRadii(body, c.fit.posed, obs.points, options.fit.outlier_m, &shape, prior);
    if (options.fit_trunk_breadth)
      RefitTrunkBreadth(body, c.fit.posed, blob, camera, &shape, prior);
  }
  if (options.fit_lengths) {
    const ShapeFitResult sf = FitBodyShape(shape, pose, obs, h, options.fit, options.shape);
    shape = sf.shape;
    const ArticulatedBody body(shape);
    BodyFitResult fit = FitBody(body, sf.pose, obs, options.fit);
    RefitRadii(body, fit.posed, obs.points, options.fit.outlier_m, &shape, prior);
    if (options.fit_trunk_breadth) RefitTrunkBreadth(body, fit.posed, blob, camera, &shape, prior);
    c.fit = FitBody(ArticulatedBody(shape), fit.pose, obs, options.fit);
    pose = c.fit.pose;
  }
  c.shape = shape;
  c.pose = pose;
  const auto lengths = shape.PartLengths();
  const auto radii = shape.PartRadii();
  for (int i = 0; i < kBodyPartCount; ++i) c.radius_ratio[i] = radii[i] / lengths[i];
  return c;
}

}  // namespace reenact::capture
