#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>

#include "common/geometry/pinhole_camera.h"
#include "common/texture/texture_mapping.h"
#include "tests/bench/bench_support.h"
#include "tests/bench/core_bench.h"

namespace reenact::bench {
namespace {

// One mapped point: stored_from_viewer of its part and the point on the viewer cylinder.
struct MappedPoint {
  Eigen::Matrix4d stored_from_viewer;
  Eigen::Vector3d viewer_point;
};

// Points on the 11 viewer-frame cylinders of random skeleton pairs, with their mappings.
std::vector<MappedPoint> MappedPoints(int pairs, int per_part, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0, 1), angle(-M_PI, M_PI);
  std::vector<MappedPoint> points;
  for (int i = 0; i < pairs; ++i) {
    const Skeleton viewer = RandomSkeleton(rng), stored = RandomSkeleton(rng);
    for (int p = 0; p < kBodyPartCount; ++p) {
      const auto [ja, jb] = PartJoints(static_cast<BodyPart>(p));
      const auto m = StoredFromViewerMapping(viewer[ja], viewer[jb], stored[ja], stored[jb]);
      if (!m) continue;
      const Eigen::Vector3d axis = viewer[jb] - viewer[ja];
      const Eigen::Vector3d e1 = axis.unitOrthogonal(), e2 = axis.normalized().cross(e1);
      const double radius = 0.3 * axis.norm();
      for (int s = 0; s < per_part; ++s) {
        const double t = angle(rng);
        points.push_back(
            {*m, viewer[ja] + unit(rng) * axis + radius * (std::cos(t) * e1 + std::sin(t) * e2)});
      }
    }
  }
  return points;
}

// Eq. 16 then the stored camera's projection, in double.
std::optional<Eigen::Vector2d> MapDouble(const MappedPoint& mp, const PinholeCamera& c) {
  const Eigen::Vector4d s = mp.stored_from_viewer * mp.viewer_point.homogeneous();
  const Eigen::Vector3d p = s.head<3>() / s.w();
  if (p.z() <= 0) return std::nullopt;
  return Eigen::Vector2d(c.fx * p.x() / p.z() + c.cx, c.fy * p.y() / p.z() + c.cy);
}

// The same in float, as the fragment shader evaluates it (float matrix, float point).
struct FloatMapping {
  Eigen::Matrix4f stored_from_viewer;
  Eigen::Vector3f viewer_point;
};

std::optional<Eigen::Vector2f> MapFloat(const FloatMapping& mp, const Eigen::Vector4f& k) {
  const Eigen::Vector4f s = mp.stored_from_viewer * mp.viewer_point.homogeneous();
  const Eigen::Vector3f p = s.head<3>() / s.w();
  if (p.z() <= 0) return std::nullopt;
  return Eigen::Vector2f(k[0] * p.x() / p.z() + k[2], k[1] * p.y() / p.z() + k[3]);
}

}  // namespace

// Eq. 6-16: the 11 per-part similarities of one output frame; then per mapped point, float
// (as the GPU evaluates Eq. 16) against double: time and the largest pixel disagreement of
// the projections into a 640x480 Kinect-like stored camera, over points inside the image
// (also in millipixels, as the table prints three decimals).
void AddMappingRows(proto::Report& report, const CoreBenchOptions& options) {
  std::mt19937 rng(11);
  std::vector<Skeleton> a, b;
  for (int i = 0; i < 1000; ++i) {
    a.push_back(RandomSkeleton(rng));
    b.push_back(RandomSkeleton(rng));
  }
  const double us = Median(TimeRepeated(options.repeats, a.size(), [&] {
    for (size_t i = 0; i < a.size(); ++i)
      for (int p = 0; p < kBodyPartCount; ++p) {
        const auto [ja, jb] = PartJoints(static_cast<BodyPart>(p));
        StoredFromViewerMapping(a[i][ja], a[i][jb], b[i][ja], b[i][jb]);
      }
  }));
  report.rows.push_back(proto::ReportRow{}
                            .Add("op", "mapping_eq16_11_parts")
                            .Add("n", static_cast<long long>(a.size()))
                            .Add("us_per_query", us));

  const PinholeCamera camera = PinholeCamera::KinectLike();
  const Eigen::Vector4f k(static_cast<float>(camera.fx), static_cast<float>(camera.fy),
                          static_cast<float>(camera.cx), static_cast<float>(camera.cy));
  const std::vector<MappedPoint> points = MappedPoints(options.quick ? 200 : 2000, 32, rng);
  std::vector<FloatMapping> float_points;
  for (const MappedPoint& mp : points)
    float_points.push_back({mp.stored_from_viewer.cast<float>(), mp.viewer_point.cast<float>()});

  double max_px = 0, sum_px = 0;
  long long inside = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const auto d = MapDouble(points[i], camera);
    if (!d || d->x() < 0 || d->y() < 0 || d->x() > camera.width || d->y() > camera.height) continue;
    const auto f = MapFloat(float_points[i], k);
    const double err =
        f ? (f->cast<double>() - *d).norm() : std::numeric_limits<double>::infinity();
    max_px = std::max(max_px, err);
    sum_px += err;
    ++inside;
  }

  double sink = 0;  // keeps the timed work observable (stored to a volatile below)
  const double double_us = Median(TimeRepeated(options.repeats, points.size(), [&] {
    for (const MappedPoint& mp : points)
      if (const auto px = MapDouble(mp, camera)) sink += px->x();
  }));
  const double float_us = Median(TimeRepeated(options.repeats, points.size(), [&] {
    for (const FloatMapping& mp : float_points)
      if (const auto px = MapFloat(mp, k)) sink += px->x();
  }));
  for (const auto& [precision, per_point_us] :
       {std::pair{"double", double_us}, std::pair{"float", float_us}}) {
    proto::ReportRow row;
    row.Add("op", std::string("mapping_point_") + precision)
        .Add("n", inside)
        .Add("us_per_query", per_point_us)
        .Add("ns_per_point", 1000 * per_point_us)
        .Add("max_px_error", std::string(precision) == "float" ? max_px : 0.0)
        .Add("max_millipx_error", std::string(precision) == "float" ? 1000 * max_px : 0.0)
        .Add("mean_millipx_error", std::string(precision) == "float" ? 1000 * sum_px / inside : 0.0)
        .Add("ratio", per_point_us / double_us);
    report.rows.push_back(row);
  }
  volatile double observed = sink;
  (void)observed;
}

}  // namespace reenact::bench
