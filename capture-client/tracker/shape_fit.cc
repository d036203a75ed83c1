#include "capture-client/tracker/shape_fit.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

#include "common/error/check.h"

namespace reenact::capture {
namespace {

constexpr int kPose = ArticulatedBody::kParameterCount;
constexpr int kParams = kPose + kShapeLengthCount;

double* LengthField(BodyShape* s, ShapeLength k) {
  switch (k) {
    case ShapeLength::kHipHalfWidth:
      return &s->hip_half_width;
    case ShapeLength::kHipDrop:
      return &s->hip_drop;
    case ShapeLength::kLowerSpine:
      return &s->lower_spine;
    case ShapeLength::kUpperSpine:
      return &s->upper_spine;
    case ShapeLength::kShoulderHalfWidth:
      return &s->shoulder_half_width;
    case ShapeLength::kShoulderDrop:
      return &s->shoulder_drop;
    case ShapeLength::kUpperArm:
      return &s->upper_arm;
    case ShapeLength::kForearm:
      return &s->forearm;
    case ShapeLength::kThigh:
      return &s->thigh;
    case ShapeLength::kShin:
      return &s->shin;
    case ShapeLength::kHeadRise:
      return &s->head_rise;
  }
  return &s->shin;
}

// The residual vector of shape_fit.h at (shape, pose).
class Residuals {
 public:
  Residuals(const BodyShape& prior, const BodyObservation& obs, double height_m,
            const BodyFitOptions& fit, const ShapeFitOptions& o)
      : prior_(prior), obs_(obs), height_m_(height_m), fit_(fit), o_(o) {
    const int caps = static_cast<int>(prior.Capsules().size());
    sil_w_ = std::sqrt(SilhouetteSampleWeight(obs, fit, caps));
    size_ = static_cast<int>(obs.points.size()) + caps * std::max(0, fit.samples_per_capsule) + 1 +
            kShapeLengthCount;
  }
  int size() const { return size_; }

  Eigen::VectorXd operator()(const BodyShape& shape, const ArticulatedPose& pose) const {
    const ArticulatedBody body(shape);
    const PosedBody3 posed = body.Pose(pose);
    struct Cap {
      Eigen::Vector3d a, ab;
      double len2, radius;
    };
    std::vector<Cap> caps;
    for (const BodyCapsule& c : body.capsules()) {
      const Eigen::Isometry3d& t = posed.sensor_from_segment[static_cast<int>(c.segment)];
      const Eigen::Vector3d a = t * c.a, b = t * c.b;
      caps.push_back({a, b - a, (b - a).squaredNorm(), c.radius});
    }
    Eigen::VectorXd r = Eigen::VectorXd::Zero(size_);
    int i = 0;
    for (const Eigen::Vector3d& p : obs_.points) {
      double best = std::numeric_limits<double>::infinity();
      for (const Cap& c : caps) {
        const double t = c.len2 > 0 ? std::clamp((p - c.a).dot(c.ab) / c.len2, 0.0, 1.0) : 0.0;
        best = std::min(best, (p - c.a - t * c.ab).norm() - c.radius);
      }
      if (best <= fit_.outlier_m)
        r[i] = (best < 0 ? -1.0 : 1.0) * std::sqrt(2 * HuberCost(best, fit_.huber_m));
      ++i;
    }
    const int m = fit_.samples_per_capsule;
    for (const Cap& c : caps)
      for (int k = 0; k < m; ++k) {
        const double t = m == 1 ? 0.5 : static_cast<double>(k) / (m - 1);
        double e = 0;
        Eigen::Vector3d grad;
        if (sil_w_ > 0 && SilhouetteResidual(obs_, c.a + t * c.ab, &e, &grad)) r[i] = sil_w_ * e;
        ++i;
      }
    const double n = static_cast<double>(obs_.points.size());
    r[i++] = std::sqrt(o_.height_weight * n) * (shape.StandingHeight() - height_m_);
    const double w = std::sqrt(o_.prior_weight * n) * o_.prior_scale_m;
    for (int k = 0; k < kShapeLengthCount; ++k) {
      const double p = GetLength(prior_, static_cast<ShapeLength>(k));
      r[i++] = p > 0 ? w * (GetLength(shape, static_cast<ShapeLength>(k)) - p) / p : 0.0;
    }
    return r;
  }

 private:
  const BodyShape& prior_;
  const BodyObservation& obs_;
  double height_m_;
  const BodyFitOptions& fit_;
  const ShapeFitOptions& o_;
  double sil_w_ = 0;
  int size_ = 0;
};

BodyShape Moved(const BodyShape& shape, const BodyShape& prior, const Eigen::VectorXd& d,
                const ShapeFitOptions& o) {
  BodyShape s = shape;
  for (int k = 0; k < kShapeLengthCount; ++k) {
    const ShapeLength l = static_cast<ShapeLength>(k);
    const double p = GetLength(prior, l);
    SetLength(&s, l,
              std::clamp(GetLength(shape, l) + d[kPose + k], o.min_ratio * p, o.max_ratio * p));
  }
  return s;
}

}  // namespace

double GetLength(const BodyShape& shape, ShapeLength k) {
  return *LengthField(const_cast<BodyShape*>(&shape), k);
}

void SetLength(BodyShape* shape, ShapeLength k, double value) { *LengthField(shape, k) = value; }

void ShapeFitOptions::Check() const {
  REENACT_CHECK(iterations >= 1, "iterations must be >= 1");
  REENACT_CHECK(height_weight >= 0 && prior_weight >= 0, "weights must be >= 0");
  REENACT_CHECK(prior_scale_m > 0 && initial_lambda > 0, "prior_scale_m, initial_lambda > 0");
  REENACT_CHECK(min_ratio > 0 && min_ratio <= 1 && max_ratio >= 1,
                "need 0 < min_ratio <= 1 <= max_ratio");
}

ShapeFitResult FitBodyShape(const BodyShape& prior, const ArticulatedPose& start,
                            const BodyObservation& obs, double height_m,
                            const BodyFitOptions& fit_options, const ShapeFitOptions& o,
                            const JointLimits& limits) {
  o.Check();
  fit_options.Check();
  REENACT_CHECK(height_m > 0 && std::isfinite(height_m), "height must be positive");
  ShapeFitResult result;
  result.shape = prior;
  result.pose = start;
  ArticulatedBody::Clamp(&result.pose, limits);
  if (obs.points.empty()) return result;

  const Residuals residuals(prior, obs, height_m, fit_options, o);
  Eigen::VectorXd r = residuals(result.shape, result.pose);
  result.initial_cost = result.cost = 0.5 * r.squaredNorm();
  double lambda = o.initial_lambda;
  Eigen::MatrixXd jac(residuals.size(), kParams);
  for (int it = 0; it < o.iterations; ++it) {
    ++result.iterations;
    const ArticulatedBody body(result.shape);
    const PosedBody3 posed = body.Pose(result.pose);
    for (int j = 0; j < kParams; ++j) {
      Eigen::VectorXd d = Eigen::VectorXd::Zero(kParams);
      const double h = j < kPose ? 1e-4 : 1e-3;
      d[j] = h;
      const Eigen::VectorXd dp = d.head(kPose), dm = -d.head(kPose);
      const BodyShape sp = Moved(result.shape, prior, d, o);
      const BodyShape sm = Moved(result.shape, prior, -d, o);
      const double step = j < kPose ? 2 * h
                                    : GetLength(sp, static_cast<ShapeLength>(j - kPose)) -
                                          GetLength(sm, static_cast<ShapeLength>(j - kPose));
      if (std::abs(step) < 1e-12 || (j >= kPose && !o.free[j - kPose])) {
        jac.col(j).setZero();
        continue;
      }
      jac.col(j) = (residuals(sp, body.Step(result.pose, posed, dp, limits)) -
                    residuals(sm, body.Step(result.pose, posed, dm, limits))) /
                   step;
    }
    const Eigen::MatrixXd h = jac.transpose() * jac;
    const Eigen::VectorXd g = jac.transpose() * r;
    bool improved = false;
    while (lambda < 1e6) {
      Eigen::MatrixXd a = h;
      a.diagonal() += lambda * h.diagonal() + Eigen::VectorXd::Constant(kParams, 1e-9);
      const Eigen::VectorXd d = a.ldlt().solve(-g);
      if (!d.allFinite()) break;
      const BodyShape shape = Moved(result.shape, prior, d, o);
      const ArticulatedPose pose = body.Step(result.pose, posed, d.head(kPose), limits);
      const Eigen::VectorXd nr = residuals(shape, pose);
      const double cost = 0.5 * nr.squaredNorm();
      if (cost < result.cost) {
        result.shape = shape;
        result.pose = pose;
        result.cost = cost;
        r = nr;
        lambda = std::max(lambda / 3, 1e-7);
        improved = true;
        break;
      }
      lambda *= 4;
    }
    if (!improved) break;
  }
  return result;
}

}  // namespace reenact::capture
