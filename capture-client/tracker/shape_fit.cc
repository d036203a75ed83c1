#include "capture-client/tracker/shape_fit.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

#include "common/error/check.h"

namespace reenact::capture {
namespace {

constexpr int kPose = ArticulatedBody::kParameterCount;

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

// One frame's data and silhouette residuals of shape_fit.h at (shape, pose).
class FrameResiduals {
 public:
  FrameResiduals(const BodyShape& prior, const BodyObservation& obs, const BodyFitOptions& fit)
      : obs_(&obs), fit_(&fit) {
    const int caps = static_cast<int>(prior.Capsules().size());
    sil_w_ = std::sqrt(SilhouetteSampleWeight(obs, fit, caps));
    size_ = static_cast<int>(obs.points.size()) + caps * std::max(0, fit.samples_per_capsule);
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
    for (const Eigen::Vector3d& p : obs_->points) {
      double best = std::numeric_limits<double>::infinity();
      for (const Cap& c : caps) {
        const double t = c.len2 > 0 ? std::clamp((p - c.a).dot(c.ab) / c.len2, 0.0, 1.0) : 0.0;
        best = std::min(best, (p - c.a - t * c.ab).norm() - c.radius);
      }
      if (best <= fit_->outlier_m)
        r[i] = (best < 0 ? -1.0 : 1.0) * std::sqrt(2 * HuberCost(best, fit_->huber_m));
      ++i;
    }
    const int m = fit_->samples_per_capsule;
    for (const Cap& c : caps)
      for (int k = 0; k < m; ++k) {
        const double t = m == 1 ? 0.5 : static_cast<double>(k) / (m - 1);
        double e = 0;
        Eigen::Vector3d grad;
        if (sil_w_ > 0 && SilhouetteResidual(*obs_, c.a + t * c.ab, &e, &grad)) r[i] = sil_w_ * e;
        ++i;
      }
    return r;
  }

 private:
  const BodyObservation* obs_;
  const BodyFitOptions* fit_;
  double sil_w_ = 0;
  int size_ = 0;
};

// The height and prior residuals (1 + kShapeLengthCount); n = data points of all frames.
Eigen::VectorXd ShapeResiduals(const BodyShape& shape, const BodyShape& prior, double height_m,
                               double n, const ShapeFitOptions& o) {
  Eigen::VectorXd r(1 + kShapeLengthCount);
  r[0] = std::sqrt(o.height_weight * n) * (shape.StandingHeight() - height_m);
  const double w = std::sqrt(o.prior_weight * n) * o.prior_scale_m;
  for (int k = 0; k < kShapeLengthCount; ++k) {
    const double p = GetLength(prior, static_cast<ShapeLength>(k));
    r[1 + k] = p > 0 ? w * (GetLength(shape, static_cast<ShapeLength>(k)) - p) / p : 0.0;
  }
  return r;
}

BodyShape Moved(const BodyShape& shape, const BodyShape& prior, const Eigen::VectorXd& d,
                const ShapeFitOptions& o) {
  BodyShape s = shape;
  for (int k = 0; k < kShapeLengthCount; ++k) {
    const ShapeLength l = static_cast<ShapeLength>(k);
    const double p = GetLength(prior, l);
    SetLength(&s, l, std::clamp(GetLength(shape, l) + d[k], o.min_ratio * p, o.max_ratio * p));
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
  const MultiFrameShapeFit m =
      FitBodyShapeFrames(prior, {start}, {&obs}, height_m, fit_options, o, limits);
  ShapeFitResult result;
  result.shape = m.shape;
  result.pose = m.poses[0];
  result.initial_cost = m.initial_cost;
  result.cost = m.cost;
  result.iterations = m.iterations;
  return result;
}

MultiFrameShapeFit FitBodyShapeFrames(const BodyShape& prior,
                                      const std::vector<ArticulatedPose>& starts,
                                      const std::vector<const BodyObservation*>& observations,
                                      double height_m, const BodyFitOptions& fit_options,
                                      const ShapeFitOptions& o, const JointLimits& limits) {
  o.Check();
  fit_options.Check();
  REENACT_CHECK(height_m > 0 && std::isfinite(height_m), "height must be positive");
  REENACT_CHECK(starts.size() == observations.size(), "one start pose per observation");
  const int frames = static_cast<int>(starts.size());
  MultiFrameShapeFit result;
  result.shape = prior;
  result.poses = starts;
  for (ArticulatedPose& p : result.poses) ArticulatedBody::Clamp(&p, limits);
  double n = 0;
  for (const BodyObservation* obs : observations) {
    REENACT_CHECK(obs != nullptr, "observation must not be null");
    n += static_cast<double>(obs->points.size());
  }
  if (frames == 0 || n == 0) return result;

  std::vector<FrameResiduals> frame_res;
  std::vector<int> row0;
  int rows = 0;
  for (const BodyObservation* obs : observations) {
    frame_res.emplace_back(prior, *obs, fit_options);
    row0.push_back(rows);
    rows += frame_res.back().size();
  }
  const int shape_row = rows;
  rows += 1 + kShapeLengthCount;
  const int params = frames * kPose + kShapeLengthCount;
  const int len0 = frames * kPose;
  const auto all_residuals = [&](const BodyShape& shape,
                                 const std::vector<ArticulatedPose>& poses) {
    Eigen::VectorXd r(rows);
    for (int f = 0; f < frames; ++f)
      r.segment(row0[f], frame_res[f].size()) = frame_res[f](shape, poses[f]);
    r.tail(1 + kShapeLengthCount) = ShapeResiduals(shape, prior, height_m, n, o);
    return r;
  };
  Eigen::VectorXd r = all_residuals(result.shape, result.poses);
  result.initial_cost = result.cost = 0.5 * r.squaredNorm();
  double lambda = o.initial_lambda;
  Eigen::MatrixXd jac = Eigen::MatrixXd::Zero(rows, params);
  for (int it = 0; it < o.iterations; ++it) {
    ++result.iterations;
    const ArticulatedBody body(result.shape);
    std::vector<PosedBody3> posed;
    for (const ArticulatedPose& p : result.poses) posed.push_back(body.Pose(p));
    jac.setZero();
    // Pose columns: only their own frame's rows.
    for (int f = 0; f < frames; ++f)
      for (int j = 0; j < kPose; ++j) {
        const double h = 1e-4;
        Eigen::VectorXd d = Eigen::VectorXd::Zero(kPose);
        d[j] = h;
        jac.block(row0[f], f * kPose + j, frame_res[f].size(), 1) =
            (frame_res[f](result.shape, body.Step(result.poses[f], posed[f], d, limits)) -
             frame_res[f](result.shape, body.Step(result.poses[f], posed[f], -d, limits))) /
            (2 * h);
      }
    // Length columns: every frame's rows and the shape rows.
    for (int k = 0; k < kShapeLengthCount; ++k) {
      if (!o.free[k]) continue;
      Eigen::VectorXd d = Eigen::VectorXd::Zero(kShapeLengthCount);
      d[k] = 1e-3;
      const BodyShape sp = Moved(result.shape, prior, d, o);
      const BodyShape sm = Moved(result.shape, prior, -d, o);
      const double step =
          GetLength(sp, static_cast<ShapeLength>(k)) - GetLength(sm, static_cast<ShapeLength>(k));
      if (std::abs(step) < 1e-12) continue;
      for (int f = 0; f < frames; ++f)
        jac.block(row0[f], len0 + k, frame_res[f].size(), 1) =
            (frame_res[f](sp, result.poses[f]) - frame_res[f](sm, result.poses[f])) / step;
      jac.block(shape_row, len0 + k, 1 + kShapeLengthCount, 1) =
          (ShapeResiduals(sp, prior, height_m, n, o) - ShapeResiduals(sm, prior, height_m, n, o)) /
          step;
    }
    const Eigen::MatrixXd h = jac.transpose() * jac;
    const Eigen::VectorXd g = jac.transpose() * r;
    bool improved = false;
    while (lambda < 1e6) {
      Eigen::MatrixXd a = h;
      a.diagonal() += lambda * h.diagonal() + Eigen::VectorXd::Constant(params, 1e-9);
      const Eigen::VectorXd d = a.ldlt().solve(-g);
      if (!d.allFinite()) break;
      const BodyShape shape = Moved(result.shape, prior, d.tail(kShapeLengthCount), o);
      std::vector<ArticulatedPose> poses(frames);
      for (int f = 0; f < frames; ++f)
        poses[f] = body.Step(result.poses[f], posed[f], d.segment(f * kPose, kPose), limits);
      const Eigen::VectorXd nr = all_residuals(shape, poses);
      const double cost = 0.5 * nr.squaredNorm();
      if (cost < result.cost) {
        result.shape = shape;
        result.poses = std::move(poses);
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
