#include "capture-client/slam/local_bundle_adjustment.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>

#include "common/error/check.h"

namespace reenact::capture::slam {

void BundleOptions::Check() const {
  REENACT_CHECK(rounds >= 1, "rounds must be >= 1");
  REENACT_CHECK(iterations >= 1, "iterations must be >= 1");
}

namespace {

using Mat63 = Eigen::Matrix<double, 6, 3>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

double TotalCost(const std::vector<Eigen::Isometry3d>& poses,
                 const std::vector<Eigen::Vector3d>& points, const BundleProblem& p,
                 const std::vector<char>& use, double fx, double fy,
                 const ObservationNoise& noise) {
  double cost = 0;
  for (size_t i = 0; i < p.observations.size(); ++i) {
    if (!use[i]) continue;
    const auto& o = p.observations[i];
    const ObservationResidual r =
        EvaluateObservation(poses[o.camera] * points[o.point], o.keypoint, fx, fy, noise);
    cost += r.valid ? r.HuberCost() : 1e3;
  }
  return cost;
}

void Classify(const BundleProblem& p, double fx, double fy, const ObservationNoise& noise,
              std::vector<char>& inlier) {
  for (size_t i = 0; i < p.observations.size(); ++i) {
    const auto& o = p.observations[i];
    inlier[i] = EvaluateObservation(p.sensor_from_world[o.camera] * p.points_in_world[o.point],
                                    o.keypoint, fx, fy, noise)
                    .IsInlier();
  }
}

}  // namespace

BundleResult SolveBundle(BundleProblem& problem, double fx, double fy,
                         const ObservationNoise& noise, const BundleOptions& options) {
  options.Check();
  noise.Check();
  REENACT_CHECK(std::isfinite(fx) && std::isfinite(fy) && fx > 0 && fy > 0,
                "focal lengths must be > 0");
  const int num_cameras = static_cast<int>(problem.sensor_from_world.size());
  const int num_points = static_cast<int>(problem.points_in_world.size());
  REENACT_CHECK(static_cast<int>(problem.camera_fixed.size()) == num_cameras,
                "camera_fixed needs one entry per camera");
  std::vector<int> variable(num_cameras, -1);
  int num_free = 0;
  for (int c = 0; c < num_cameras; ++c) {
    if (!problem.camera_fixed[c]) variable[c] = num_free++;
  }
  REENACT_CHECK(num_free < num_cameras, "at least one camera must be fixed");
  std::vector<std::vector<int>> point_observations(num_points);
  for (size_t i = 0; i < problem.observations.size(); ++i) {
    const auto& o = problem.observations[i];
    REENACT_CHECK(o.camera >= 0 && o.camera < num_cameras && o.point >= 0 && o.point < num_points,
                  "observation index out of range");
    point_observations[o.point].push_back(static_cast<int>(i));
  }

  BundleResult result;
  const size_t n_obs = problem.observations.size();
  std::vector<char> use(n_obs, 1);
  result.inlier.assign(n_obs, 1);
  result.initial_cost =
      TotalCost(problem.sensor_from_world, problem.points_in_world, problem, use, fx, fy, noise);

  const int dim = 6 * num_free;
  std::vector<Eigen::Matrix3d> hpp(num_points);
  std::vector<Eigen::Vector3d> gp(num_points);
  std::vector<Mat63> hcp(n_obs);
  Eigen::MatrixXd hcc(dim, dim);
  Eigen::VectorXd gc(dim);

  for (int round = 0; round < options.rounds; ++round) {
    double lambda = 1e-4;
    double cost =
        TotalCost(problem.sensor_from_world, problem.points_in_world, problem, use, fx, fy, noise);
    for (int it = 0; it < options.iterations; ++it) {
      hcc.setZero();
      gc.setZero();
      for (int p = 0; p < num_points; ++p) {
        hpp[p].setZero();
        gp[p].setZero();
      }
      for (size_t i = 0; i < n_obs; ++i) {
        hcp[i].setZero();
        if (!use[i]) continue;
        const auto& o = problem.observations[i];
        const Eigen::Isometry3d& pose = problem.sensor_from_world[o.camera];
        const Eigen::Vector3d pc = pose * problem.points_in_world[o.point];
        const ObservationResidual r = EvaluateObservation(pc, o.keypoint, fx, fy, noise);
        if (!r.valid) continue;
        const double w = r.HuberWeight();
        const Eigen::Matrix3d jl = r.d_r_d_point * pose.linear();
        hpp[o.point].noalias() += w * jl.transpose() * jl;
        gp[o.point].noalias() += w * jl.transpose() * r.r;
        const int v = variable[o.camera];
        if (v < 0) continue;
        const Eigen::Matrix<double, 3, 6> jc = r.d_r_d_point * PointJacobianWrtPose(pc);
        hcc.block<6, 6>(6 * v, 6 * v).noalias() += w * jc.transpose() * jc;
        gc.segment<6>(6 * v).noalias() += w * jc.transpose() * r.r;
        hcp[i].noalias() = w * jc.transpose() * jl;
      }

      bool accepted = false;
      for (int attempt = 0; attempt < 8 && !accepted; ++attempt) {
        Eigen::MatrixXd s = hcc;
        s.diagonal() += lambda * (hcc.diagonal().array() + 1e-9).matrix();
        Eigen::VectorXd rhs = -gc;
        std::vector<Eigen::Matrix3d> hpp_inv(num_points);
        for (int p = 0; p < num_points; ++p) {
          Eigen::Matrix3d d = hpp[p];
          d.diagonal() += lambda * (hpp[p].diagonal().array() + 1e-9).matrix();
          hpp_inv[p] = d.inverse();
          if (!hpp_inv[p].allFinite()) hpp_inv[p].setZero();
          const auto& obs = point_observations[p];
          for (int a : obs) {
            const int va = variable[problem.observations[a].camera];
            if (va < 0 || !use[a]) continue;
            const Mat63 t = hcp[a] * hpp_inv[p];
            rhs.segment<6>(6 * va) += t * gp[p];
            for (int b : obs) {
              const int vb = variable[problem.observations[b].camera];
              if (vb < 0 || !use[b]) continue;
              s.block<6, 6>(6 * va, 6 * vb).noalias() -= t * hcp[b].transpose();
            }
          }
        }
        Eigen::VectorXd dc = Eigen::VectorXd::Zero(dim);
        if (dim > 0) dc = s.ldlt().solve(rhs);
        if (!dc.allFinite()) {
          lambda *= 10;
          continue;
        }
        std::vector<Eigen::Isometry3d> candidate_poses = problem.sensor_from_world;
        std::vector<Eigen::Vector3d> candidate_points = problem.points_in_world;
        for (int c = 0; c < num_cameras; ++c) {
          if (variable[c] >= 0) {
            candidate_poses[c] =
                ApplyPoseUpdate(dc.segment<6>(6 * variable[c]), problem.sensor_from_world[c]);
          }
        }
        for (int p = 0; p < num_points; ++p) {
          Eigen::Vector3d b = -gp[p];
          for (int a : point_observations[p]) {
            const int va = variable[problem.observations[a].camera];
            if (va >= 0 && use[a]) b -= hcp[a].transpose() * dc.segment<6>(6 * va);
          }
          const Eigen::Vector3d dp = hpp_inv[p] * b;
          if (dp.allFinite()) candidate_points[p] += dp;
        }
        const double candidate_cost =
            TotalCost(candidate_poses, candidate_points, problem, use, fx, fy, noise);
        if (candidate_cost < cost) {
          const bool converged = cost - candidate_cost <= 1e-9 * cost;
          problem.sensor_from_world = std::move(candidate_poses);
          problem.points_in_world = std::move(candidate_points);
          cost = candidate_cost;
          lambda = std::max(1e-9, lambda / 3);
          ++result.iterations;
          accepted = !converged;
          if (converged) break;
        } else {
          lambda *= 8;
        }
      }
      if (!accepted) break;
    }
    Classify(problem, fx, fy, noise, result.inlier);
    use = result.inlier;
  }
  result.final_cost =
      TotalCost(problem.sensor_from_world, problem.points_in_world, problem, use, fx, fy, noise);
  return result;
}

}  // namespace reenact::capture::slam
