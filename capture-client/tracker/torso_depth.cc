#include "capture-client/tracker/torso_depth.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "capture-client/tracker/body_fit.h"
#include "common/error/check.h"
#include "common/estimate/median.h"

namespace reenact::capture {

namespace {

constexpr BodySegment kTrunkSegments[] = {BodySegment::kPelvis, BodySegment::kLowerSpine,
                                          BodySegment::kChest};

// Whether the silhouette really ends beyond the trunk's point p (sensor frame), looking
// outwards along `outward` (unit, sensor frame) by step_m: the grid pixel there is not the
// person's, or its reading lies more than min_gap_m behind p (the trunk's edge in front of
// another part). A person pixel at p's depth or nearer (an arm in front of the edge, or
// touching it) hides where the trunk ends; so does the image's edge.
bool EdgeIsFree(const PersonBlob& blob, const PinholeCamera& camera, const Eigen::Vector3d& p,
                const Eigen::Vector3d& outward, double step_m, double min_gap_m) {
  const auto px = camera.Project(p + step_m * outward);
  if (!px) return false;
  const int u = static_cast<int>(std::floor(px->x() / blob.grid_step_px));
  const int v = static_cast<int>(std::floor(px->y() / blob.grid_step_px));
  if (u < 0 || v < 0 || u >= blob.mask.width || v >= blob.mask.height) return false;
  if (blob.mask.at(u, v) == 0) return true;
  const float z = blob.depth_m.at(u, v);
  return z > 0 && z > p.z() + min_gap_m;
}

}  // namespace

void TorsoDepthOptions::Check() const {
  REENACT_CHECK(max_distance_m > 0 && slice_m > 0, "max_distance_m and slice_m must be > 0");
  REENACT_CHECK(min_slice_points >= 2 && min_slices >= 1,
                "min_slice_points must be >= 2 and min_slices >= 1");
  REENACT_CHECK(max_side_deg >= 0 && max_side_deg <= 90, "max_side_deg must be in [0, 90]");
  REENACT_CHECK(side_frames >= 1, "side_frames must be >= 1");
  REENACT_CHECK(min_depth_ratio > 0 && min_depth_ratio <= 1, "min_depth_ratio in (0, 1]");
  REENACT_CHECK(min_edge_gap_m >= 0, "min_edge_gap_m must be >= 0");
  REENACT_CHECK(quantile >= 0 && quantile <= 1, "quantile must be in [0, 1]");
}

std::vector<TrunkWidth> MeasureTrunkWidths(const ArticulatedBody& body, const PosedBody3& posed,
                                           const PersonBlob& blob, const PinholeCamera& camera,
                                           const TorsoDepthOptions& options) {
  options.Check();
  std::vector<TrunkWidth> out;
  if (blob.status != DetectStatus::kOk || blob.points.empty() || blob.grid_step_px < 1 ||
      blob.mask.width <= 0 || blob.mask.height <= 0 || blob.depth_m.width != blob.mask.width ||
      blob.depth_m.height != blob.mask.height)
    return out;

  // The segments seen near side-on, each with its axis range (from its capsules), its line of
  // sight's horizontal part (segment frame) and the direction across it. Cheap, so that a
  // frame without a side view costs no more.
  struct View {
    BodySegment segment = BodySegment::kPelvis;
    double z_lo = std::numeric_limits<double>::infinity(), z_hi = -z_lo;
    double depth = 0, sin_from_side = 0;
    Eigen::Vector2d across = Eigen::Vector2d::Zero();
  };
  std::vector<View> views;
  const double max_sin = std::sin(options.max_side_deg * std::numbers::pi / 180);
  for (const BodySegment s : kTrunkSegments) {
    View v;
    v.segment = s;
    for (const BodyCapsule& c : body.capsules())
      if (c.segment == s) {
        v.z_lo = std::min({v.z_lo, c.a.z(), c.b.z()});
        v.z_hi = std::max({v.z_hi, c.a.z(), c.b.z()});
      }
    if (!(v.z_hi > v.z_lo)) continue;
    const Eigen::Isometry3d& sensor_from_segment = posed.sensor_from_segment[static_cast<int>(s)];
    const Eigen::Vector3d centre =
        sensor_from_segment * Eigen::Vector3d(0, 0, 0.5 * (v.z_lo + v.z_hi));
    if (!(centre.z() > 0)) continue;
    const Eigen::Vector3d sight = sensor_from_segment.linear().transpose() * centre.normalized();
    const Eigen::Vector2d horizontal(sight.x(), sight.y());
    if (horizontal.norm() < 1.0 / 3) continue;
    v.depth = centre.z();
    v.sin_from_side = std::abs(horizontal.x()) / horizontal.norm();
    v.across = Eigen::Vector2d(-horizontal.y(), horizontal.x()).normalized();
    if (v.sin_from_side <= max_sin) views.push_back(v);
  }
  if (views.empty()) return out;

  // Each point's owner: the trunk segment of its nearest capsule, or -1.
  std::vector<int> owner = NearestSegments(body, posed, blob.points, options.max_distance_m);
  for (int& o : owner)
    if (o >= 0 && std::find(std::begin(kTrunkSegments), std::end(kTrunkSegments),
                            static_cast<BodySegment>(o)) == std::end(kTrunkSegments))
      o = -1;

  for (const View& v : views) {
    const int si = static_cast<int>(v.segment);
    const Eigen::Isometry3d& sensor_from_segment = posed.sensor_from_segment[si];
    const Eigen::Isometry3d segment_from_sensor = sensor_from_segment.inverse();
    const double grid_m = blob.grid_step_px * v.depth / camera.fx;
    const double slice_m = std::max(options.slice_m, 2 * grid_m);
    const int slices = std::max(1, static_cast<int>(std::ceil((v.z_hi - v.z_lo) / slice_m)));
    std::vector<double> lo(slices, std::numeric_limits<double>::infinity());
    std::vector<double> hi(slices, -std::numeric_limits<double>::infinity());
    std::vector<int> count(slices, 0), lo_point(slices, -1), hi_point(slices, -1);
    for (size_t i = 0; i < blob.points.size(); ++i) {
      if (owner[i] != si) continue;
      const Eigen::Vector3d q = segment_from_sensor * blob.points[i];
      if (q.z() < v.z_lo || q.z() >= v.z_hi) continue;
      const int k = std::min(slices - 1, static_cast<int>((q.z() - v.z_lo) / slice_m));
      const double u = v.across.dot(Eigen::Vector2d(q.x(), q.y()));
      if (u < lo[k]) lo[k] = u, lo_point[k] = static_cast<int>(i);
      if (u > hi[k]) hi[k] = u, hi_point[k] = static_cast<int>(i);
      ++count[k];
    }
    // A slice counts where the silhouette ends beyond both its extreme points (EdgeIsFree, a
    // step of two grid spacings): an arm in front of the trunk's edge, or the image's edge,
    // would make it read narrow.
    const Eigen::Vector3d outward =
        sensor_from_segment.linear() * Eigen::Vector3d(v.across.x(), v.across.y(), 0);
    std::vector<double> widths;
    for (int k = 0; k < slices; ++k)
      if (count[k] >= options.min_slice_points &&
          EdgeIsFree(blob, camera, blob.points[lo_point[k]], -outward, 2 * grid_m,
                     options.min_edge_gap_m) &&
          EdgeIsFree(blob, camera, blob.points[hi_point[k]], outward, 2 * grid_m,
                     options.min_edge_gap_m))
        widths.push_back(hi[k] - lo[k] + grid_m);
    if (static_cast<int>(widths.size()) < options.min_slices) continue;
    out.push_back({.segment = v.segment,
                   .half_width_m = 0.5 * Median(widths),
                   .sin_from_side = v.sin_from_side});
  }
  return out;
}

BodyShape WithTorsoDepth(const BodyShape& shape, double half_depth_m, double min_depth_ratio) {
  REENACT_CHECK(half_depth_m > 0 && std::isfinite(half_depth_m), "half depth must be positive");
  REENACT_CHECK(min_depth_ratio > 0 && min_depth_ratio <= 1, "min_depth_ratio in (0, 1]");
  BodyShape s = shape;
  const double half_breadth = shape.torso_radius + shape.torso_half_spread;
  s.torso_radius = std::clamp(half_depth_m, min_depth_ratio * half_breadth, half_breadth);
  s.torso_half_spread = half_breadth - s.torso_radius;
  return s;
}

std::optional<double> MeasureTrunkBreadth(const ArticulatedBody& body, const PosedBody3& posed,
                                          const PersonBlob& blob, const PinholeCamera& camera,
                                          double max_facing_deg, const TorsoDepthOptions& options) {
  REENACT_CHECK(max_facing_deg >= 0 && max_facing_deg <= 90, "max_facing_deg in [0, 90]");
  TorsoDepthOptions every_view = options;
  every_view.max_side_deg = 90;
  const double min_sin = std::cos(max_facing_deg * std::numbers::pi / 180);
  for (const TrunkWidth& w : MeasureTrunkWidths(body, posed, blob, camera, every_view))
    if (w.segment == BodySegment::kLowerSpine && w.sin_from_side >= min_sin - 1e-12 &&
        w.half_width_m > 0 && std::isfinite(w.half_width_m))
      return w.half_width_m;
  return std::nullopt;
}

BodyShape WithTorsoBreadth(const BodyShape& shape, double half_breadth_m) {
  REENACT_CHECK(half_breadth_m > 0 && std::isfinite(half_breadth_m),
                "half breadth must be positive");
  BodyShape s = shape;
  s.torso_radius = std::min(shape.torso_radius, half_breadth_m);
  s.torso_half_spread = half_breadth_m - s.torso_radius;
  return s;
}

TorsoDepthCollector::TorsoDepthCollector(const TorsoDepthOptions& options) : options_(options) {
  options_.Check();
}

std::optional<double> TorsoDepthCollector::Add(const std::vector<TrunkWidth>& widths) {
  if (done_) return std::nullopt;
  bool side = false;
  for (const TrunkWidth& w : widths)
    if (w.half_width_m > 0 && std::isfinite(w.half_width_m)) {
      half_widths_.push_back(w.half_width_m);
      side = true;
    }
  if (!side || ++frames_ < options_.side_frames) return std::nullopt;
  done_ = true;
  return Percentile(half_widths_, options_.quantile);
}

void TorsoDepthCollector::Clear() {
  half_widths_.clear();
  frames_ = 0;
  done_ = false;
}

}  // namespace reenact::capture
