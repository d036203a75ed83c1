#include "vision/features/depth_plane_fit.h"

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "common/error/check.h"

namespace reenact::vision {

void DepthPlaneFitOptions::Check() const {
  REENACT_CHECK(radius_px >= 1 && radius_px <= 16, "depth plane fit radius_px in [1, 16]");
  REENACT_CHECK(rel_tolerance > 0 && rel_tolerance < 1, "depth plane fit rel_tolerance in (0, 1)");
  REENACT_CHECK(min_support > 0 && min_support <= 1, "depth plane fit min_support in (0, 1]");
}

namespace {

struct Sample {
  double du, dv, w;
};

// Least squares plane w = a + b du + c dv through the samples flagged in `use`.
std::optional<Eigen::Vector3d> FitPlane(const std::vector<Sample>& samples,
                                        const std::vector<char>& use) {
  Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
  Eigen::Vector3d atb = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < samples.size(); ++i) {
    if (!use[i]) continue;
    const Eigen::Vector3d row(1, samples[i].du, samples[i].dv);
    ata += row * row.transpose();
    atb += row * samples[i].w;
  }
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(ata);
  // Readings on one line (or fewer than 3) leave the plane undetermined.
  if (ldlt.info() != Eigen::Success || std::abs(ata.determinant()) < 1e-9 * ata.trace()) {
    return std::nullopt;
  }
  return Eigen::Vector3d(ldlt.solve(atb));
}

}  // namespace

std::optional<double> FitDepthPlane(const ImageDepthMm& depth, double depth_scale_m, double x,
                                    double y, const DepthPlaneFitOptions& options) {
  options.Check();
  REENACT_CHECK(std::isfinite(depth_scale_m) && depth_scale_m > 0, "depth_scale_m must be > 0");
  if (!std::isfinite(x) || !std::isfinite(y)) return std::nullopt;
  const int u0 = static_cast<int>(std::lround(x)), v0 = static_cast<int>(std::lround(y));
  const int r = options.radius_px;
  std::vector<Sample> samples;
  samples.reserve(static_cast<size_t>((2 * r + 1) * (2 * r + 1)));
  for (int dv = -r; dv <= r; ++dv) {
    for (int du = -r; du <= r; ++du) {
      if (!depth.Contains(u0 + du, v0 + dv)) continue;
      const uint16_t mm = depth.at(u0 + du, v0 + dv);
      if (mm == 0) continue;
      samples.push_back(
          {static_cast<double>(du), static_cast<double>(dv), 1.0 / (mm * depth_scale_m)});
    }
  }
  const double window = (2.0 * r + 1) * (2.0 * r + 1);
  const auto needed =
      std::max<size_t>(static_cast<size_t>(std::ceil(options.min_support * window)), 3);
  if (!depth.Contains(u0, v0) || depth.at(u0, v0) == 0 || samples.size() < needed) {
    return std::nullopt;
  }
  // The first plane goes through the readings near the keypoint's own (the surface it lies
  // on); each later one through the readings that agree with the previous plane.
  const double w0 = 1.0 / (depth.at(u0, v0) * depth_scale_m);
  std::vector<char> use(samples.size());
  for (size_t i = 0; i < samples.size(); ++i) {
    use[i] = std::abs(samples[i].w - w0) <= options.rel_tolerance * w0;
  }
  std::optional<Eigen::Vector3d> plane = FitPlane(samples, use);
  for (int round = 0; round < 2 && plane; ++round) {
    const double tolerance = options.rel_tolerance * std::abs((*plane)(0));
    size_t kept = 0;
    for (size_t i = 0; i < samples.size(); ++i) {
      const Sample& s = samples[i];
      const double residual = s.w - ((*plane)(0) + (*plane)(1) * s.du + (*plane)(2) * s.dv);
      use[i] = std::abs(residual) <= tolerance;
      kept += use[i];
    }
    if (kept < needed) return std::nullopt;
    plane = FitPlane(samples, use);
  }
  if (!plane) return std::nullopt;
  const double w = (*plane)(0) + (*plane)(1) * (x - u0) + (*plane)(2) * (y - v0);
  if (!std::isfinite(w) || w <= 0) return std::nullopt;
  return 1.0 / w;
}

}  // namespace reenact::vision
