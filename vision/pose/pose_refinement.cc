#include "vision/pose/pose_refinement.h"

#include <Eigen/Cholesky>
#include <cmath>

#include "common/error/check.h"

namespace reenact::vision {

void PoseRefinementOptions::Check() const {
  REENACT_CHECK(rounds >= 1, "rounds must be >= 1");
  REENACT_CHECK(iterations >= 1, "iterations must be >= 1");
}

namespace {

double Cost(const Eigen::Isometry3d& pose, const std::vector<PointObservation>& obs,
            const std::vector<char>& use, double fx, double fy, const ObservationNoise& noise) {
  double cost = 0;
  for (size_t i = 0; i < obs.size(); ++i) {
    if (!use[i]) continue;
    const ObservationResidual r =
        EvaluateObservation(pose * obs[i].point_in_world, obs[i].observation, fx, fy, noise);
    cost += r.valid ? r.HuberCost() : 1e3;  // behind the camera: a large constant penalty
  }
  return cost;
}

int Classify(const Eigen::Isometry3d& pose, const std::vector<PointObservation>& obs, double fx,
             double fy, const ObservationNoise& noise, std::vector<char>& inlier) {
  int n = 0;
  for (size_t i = 0; i < obs.size(); ++i) {
    inlier[i] = EvaluateObservation(pose * obs[i].point_in_world, obs[i].observation, fx, fy, noise)
                    .IsInlier();
    n += inlier[i];
  }
  return n;
}

}  // namespace

// A round ends when the accepted update is below this (radians and metres): 0.1 micrometre
// at a metre, far below what the pixels tell, where 1e-10 ran every round to its last
// iteration.
constexpr double kConvergedStep = 1e-7;

PoseRefinementResult RefinePose(const Eigen::Isometry3d& initial_sensor_from_world,
                                const std::vector<PointObservation>& observations, double fx,
                                double fy, const ObservationNoise& noise,
                                const PoseRefinementOptions& options) {
  options.Check();
  noise.Check();
  REENACT_CHECK(std::isfinite(fx) && std::isfinite(fy) && fx > 0 && fy > 0,
                "focal lengths must be > 0");
  PoseRefinementResult result;
  result.sensor_from_world = initial_sensor_from_world;
  result.inlier.assign(observations.size(), 1);
  if (observations.size() < 3 || !initial_sensor_from_world.matrix().allFinite()) {
    result.inlier.assign(observations.size(), 0);
    if (initial_sensor_from_world.matrix().allFinite()) {
      result.num_inliers =
          Classify(initial_sensor_from_world, observations, fx, fy, noise, result.inlier);
    }
    return result;
  }

  std::vector<char> use(observations.size(), 1);
  Eigen::Isometry3d pose = initial_sensor_from_world;
  for (int round = 0; round < options.rounds; ++round) {
    double lambda = 1e-4;
    double cost = Cost(pose, observations, use, fx, fy, noise);
    for (int it = 0; it < options.iterations; ++it) {
      Eigen::Matrix<double, 6, 6> h = Eigen::Matrix<double, 6, 6>::Zero();
      Eigen::Matrix<double, 6, 1> g = Eigen::Matrix<double, 6, 1>::Zero();
      int used = 0;
      for (size_t i = 0; i < observations.size(); ++i) {
        if (!use[i]) continue;
        const Eigen::Vector3d pc = pose * observations[i].point_in_world;
        const ObservationResidual r =
            EvaluateObservation(pc, observations[i].observation, fx, fy, noise);
        if (!r.valid) continue;
        const Eigen::Matrix<double, 3, 6> j = r.d_r_d_point * PointJacobianWrtPose(pc);
        const double w = r.HuberWeight();
        h.noalias() += w * j.transpose() * j;
        g.noalias() += w * j.transpose() * r.r;
        ++used;
      }
      if (used < 3) break;
      bool improved = false;
      for (int attempt = 0; attempt < 10 && !improved; ++attempt) {
        Eigen::Matrix<double, 6, 6> damped = h;
        damped.diagonal() += lambda * (h.diagonal().array() + 1e-9).matrix();
        const Eigen::Matrix<double, 6, 1> delta = damped.ldlt().solve(-g);
        if (!delta.allFinite()) break;
        const Eigen::Isometry3d candidate = ApplyPoseUpdate(delta, pose);
        const double candidate_cost = Cost(candidate, observations, use, fx, fy, noise);
        if (candidate_cost < cost) {
          pose = candidate;
          lambda = std::max(1e-9, lambda / 3);
          improved = delta.norm() > kConvergedStep && (cost - candidate_cost) > 1e-12 * cost;
          cost = candidate_cost;
          if (!improved) break;
        } else {
          lambda *= 8;
        }
      }
      if (!improved) break;
    }
    const int n = Classify(pose, observations, fx, fy, noise, result.inlier);
    if (n < 3) break;
    use = result.inlier;
  }
  result.sensor_from_world = pose;
  result.num_inliers = Classify(pose, observations, fx, fy, noise, result.inlier);
  if (result.num_inliers >= 3) {
    for (size_t i = 0; i < observations.size(); ++i) {
      if (!result.inlier[i]) continue;
      const Eigen::Vector3d pc = pose * observations[i].point_in_world;
      const ObservationResidual r =
          EvaluateObservation(pc, observations[i].observation, fx, fy, noise);
      if (!r.valid) continue;
      const Eigen::Matrix<double, 3, 6> j = r.d_r_d_point * PointJacobianWrtPose(pc);
      result.information.noalias() += r.HuberWeight() * j.transpose() * j;
    }
  }
  return result;
}

}  // namespace reenact::vision
