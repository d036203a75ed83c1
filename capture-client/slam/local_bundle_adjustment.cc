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

// Levenberg-Marquardt on one bundle problem: the cameras' normal equations reduced by the
// Schur complement of the points, which are eliminated one by one.
class BundleSolver {
 public:
  // Preconditions (CHECK): camera_fixed has one entry per camera and some are fixed; the
  // observations' indices are in range.
  BundleSolver(BundleProblem& problem, double fx, double fy, const ObservationNoise& noise)
      : problem_(problem),
        fx_(fx),
        fy_(fy),
        noise_(noise),
        num_cameras_(static_cast<int>(problem.sensor_from_world.size())),
        num_points_(static_cast<int>(problem.points_in_world.size())) {
    IndexUnknowns();
  }

  BundleResult Solve(const BundleOptions& options) {
    BundleResult result;
    const size_t n_obs = problem_.observations.size();
    use_.assign(n_obs, 1);
    result.inlier.assign(n_obs, 1);
    result.initial_cost = Cost(problem_.sensor_from_world, problem_.points_in_world);
    AllocateNormalEquations();
    for (int round = 0; round < options.rounds; ++round) {
      double lambda = 1e-4;
      double cost = Cost(problem_.sensor_from_world, problem_.points_in_world);
      for (int it = 0; it < options.iterations; ++it) {
        Linearise();
        if (!Step(lambda, cost, result.iterations)) break;
      }
      Classify(problem_, fx_, fy_, noise_, result.inlier);
      use_ = result.inlier;
    }
    result.final_cost = Cost(problem_.sensor_from_world, problem_.points_in_world);
    return result;
  }

 private:
  void IndexUnknowns() {
    REENACT_CHECK(static_cast<int>(problem_.camera_fixed.size()) == num_cameras_,
                  "camera_fixed needs one entry per camera");
    variable_.assign(num_cameras_, -1);
    for (int c = 0; c < num_cameras_; ++c) {
      if (!problem_.camera_fixed[c]) variable_[c] = num_free_++;
    }
    REENACT_CHECK(num_free_ < num_cameras_, "at least one camera must be fixed");
    point_observations_.resize(num_points_);
    for (size_t i = 0; i < problem_.observations.size(); ++i) {
      const auto& o = problem_.observations[i];
      REENACT_CHECK(
          o.camera >= 0 && o.camera < num_cameras_ && o.point >= 0 && o.point < num_points_,
          "observation index out of range");
      point_observations_[o.point].push_back(static_cast<int>(i));
    }
  }

  double Cost(const std::vector<Eigen::Isometry3d>& poses,
              const std::vector<Eigen::Vector3d>& points) const {
    return TotalCost(poses, points, problem_, use_, fx_, fy_, noise_);
  }

  void AllocateNormalEquations() {
    const int dim = 6 * num_free_;
    hpp_.resize(num_points_);
    gp_.resize(num_points_);
    hcp_.resize(problem_.observations.size());
    hcc_.resize(dim, dim);
    gc_.resize(dim);
  }

  // The normal equations of the used observations (Huber-weighted) at the current estimate.
  void Linearise() {
    hcc_.setZero();
    gc_.setZero();
    for (int p = 0; p < num_points_; ++p) {
      hpp_[p].setZero();
      gp_[p].setZero();
    }
    for (size_t i = 0; i < problem_.observations.size(); ++i) {
      hcp_[i].setZero();
      if (!use_[i]) continue;
      const auto& o = problem_.observations[i];
      const Eigen::Isometry3d& pose = problem_.sensor_from_world[o.camera];
      const Eigen::Vector3d pc = pose * problem_.points_in_world[o.point];
      const ObservationResidual r = EvaluateObservation(pc, o.keypoint, fx_, fy_, noise_);
      if (!r.valid) continue;
      const double w = r.HuberWeight();
      const Eigen::Matrix3d jl = r.d_r_d_point * pose.linear();
      hpp_[o.point].noalias() += w * jl.transpose() * jl;
      gp_[o.point].noalias() += w * jl.transpose() * r.r;
      const int v = variable_[o.camera];
      if (v < 0) continue;
      const Eigen::Matrix<double, 3, 6> jc = r.d_r_d_point * PointJacobianWrtPose(pc);
      hcc_.block<6, 6>(6 * v, 6 * v).noalias() += w * jc.transpose() * jc;
      gc_.segment<6>(6 * v).noalias() += w * jc.transpose() * r.r;
      hcp_[i].noalias() = w * jc.transpose() * jl;
    }
  }

  // Up to 8 damped steps until one lowers the cost, which is then taken; false when none
  // does or the decrease is negligible (converged).
  bool Step(double& lambda, double& cost, int& iterations) {
    for (int attempt = 0; attempt < 8; ++attempt) {
      std::vector<Eigen::Matrix3d> hpp_inv(num_points_);
      const Eigen::VectorXd dc = SolveCameras(lambda, hpp_inv);
      if (!dc.allFinite()) {
        lambda *= 10;
        continue;
      }
      std::vector<Eigen::Isometry3d> candidate_poses = problem_.sensor_from_world;
      std::vector<Eigen::Vector3d> candidate_points = problem_.points_in_world;
      Update(dc, hpp_inv, candidate_poses, candidate_points);
      const double candidate_cost = Cost(candidate_poses, candidate_points);
      if (candidate_cost < cost) {
        const bool converged = cost - candidate_cost <= 1e-9 * cost;
        problem_.sensor_from_world = std::move(candidate_poses);
        problem_.points_in_world = std::move(candidate_points);
        cost = candidate_cost;
        lambda = std::max(1e-9, lambda / 3);
        ++iterations;
        return !converged;
      }
      lambda *= 8;
    }
    return false;
  }

  // The free cameras' step at damping lambda from the reduced camera system; the points'
  // damped inverse blocks into hpp_inv (zero where not invertible).
  Eigen::VectorXd SolveCameras(double lambda, std::vector<Eigen::Matrix3d>& hpp_inv) const {
    const int dim = 6 * num_free_;
    Eigen::MatrixXd s = hcc_;
    s.diagonal() += lambda * (hcc_.diagonal().array() + 1e-9).matrix();
    Eigen::VectorXd rhs = -gc_;
    for (int p = 0; p < num_points_; ++p) {
      Eigen::Matrix3d d = hpp_[p];
      d.diagonal() += lambda * (hpp_[p].diagonal().array() + 1e-9).matrix();
      hpp_inv[p] = d.inverse();
      if (!hpp_inv[p].allFinite()) hpp_inv[p].setZero();
      const auto& obs = point_observations_[p];
      for (int a : obs) {
        const int va = variable_[problem_.observations[a].camera];
        if (va < 0 || !use_[a]) continue;
        const Mat63 t = hcp_[a] * hpp_inv[p];
        rhs.segment<6>(6 * va) += t * gp_[p];
        for (int b : obs) {
          const int vb = variable_[problem_.observations[b].camera];
          if (vb < 0 || !use_[b]) continue;
          s.block<6, 6>(6 * va, 6 * vb).noalias() -= t * hcp_[b].transpose();
        }
      }
    }
    Eigen::VectorXd dc = Eigen::VectorXd::Zero(dim);
    if (dim > 0) dc = s.ldlt().solve(rhs);
    return dc;
  }

  // Applies the camera step dc to the free poses and back-substitutes the points' steps.
  void Update(const Eigen::VectorXd& dc, const std::vector<Eigen::Matrix3d>& hpp_inv,
              std::vector<Eigen::Isometry3d>& poses, std::vector<Eigen::Vector3d>& points) const {
    for (int c = 0; c < num_cameras_; ++c) {
      if (variable_[c] >= 0) {
        poses[c] = ApplyPoseUpdate(dc.segment<6>(6 * variable_[c]), problem_.sensor_from_world[c]);
      }
    }
    for (int p = 0; p < num_points_; ++p) {
      Eigen::Vector3d b = -gp_[p];
      for (int a : point_observations_[p]) {
        const int va = variable_[problem_.observations[a].camera];
        if (va >= 0 && use_[a]) b -= hcp_[a].transpose() * dc.segment<6>(6 * va);
      }
      const Eigen::Vector3d dp = hpp_inv[p] * b;
      if (dp.allFinite()) points[p] += dp;
    }
  }

  BundleProblem& problem_;
  const double fx_, fy_;
  const ObservationNoise& noise_;
  const int num_cameras_, num_points_;
  std::vector<int> variable_;  // per camera: its index among the free ones, -1 when fixed
  int num_free_ = 0;
  std::vector<std::vector<int>> point_observations_;  // per point: its observations
  std::vector<char> use_;  // per observation: counted (an inlier of the round before)
  // Normal equations: per point (hpp_, gp_), per observation the camera-point block (hcp_),
  // the free cameras (hcc_, gc_).
  std::vector<Eigen::Matrix3d> hpp_;
  std::vector<Eigen::Vector3d> gp_;
  std::vector<Mat63> hcp_;
  Eigen::MatrixXd hcc_;
  Eigen::VectorXd gc_;
};

}  // namespace

BundleResult SolveBundle(BundleProblem& problem, double fx, double fy,
                         const ObservationNoise& noise, const BundleOptions& options) {
  options.Check();
  noise.Check();
  REENACT_CHECK(std::isfinite(fx) && std::isfinite(fy) && fx > 0 && fy > 0,
                "focal lengths must be > 0");
  return BundleSolver(problem, fx, fy, noise).Solve(options);
}

}  // namespace reenact::capture::slam
