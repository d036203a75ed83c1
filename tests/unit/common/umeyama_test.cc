// Umeyama similarity (Eq. 17-24): exact recovery, degenerate input, the reflection case,
// far-from-origin coordinates, extreme scales, and noise bounded by first-order theory.
#include "common/align/umeyama.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "common/error/check.h"
#include "common/geometry/rotation.h"

namespace reenact {
namespace {

Eigen::Matrix3d RandomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));  // uniform on SO(3) once normalised
  return q.normalized().toRotationMatrix();
}

std::vector<Eigen::Vector3d> Apply(const Sim3& t, const std::vector<Eigen::Vector3d>& points) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& p : points) out.push_back(t * p);
  return out;
}

std::vector<Eigen::Vector3d> Cloud(int n, double spread, const Eigen::Vector3d& centre,
                                   uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-spread, spread);
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < n; ++i) out.push_back(centre + Eigen::Vector3d(u(rng), u(rng), u(rng)));
  return out;
}

// Angle of R_est R_true^T.
double RotationError(const Eigen::Matrix3d& est, const Eigen::Matrix3d& truth) {
  return RotationAngle(est * truth.transpose());
}

TEST(Umeyama, RecoversAnExactSimilarity) {
  const Sim3 truth(2.5, *Theta({1, -2, 0.5}, 1.1), {0.3, -4, 2});
  const auto a = Cloud(10, 1, {0, 0, 0}, 1);
  const UmeyamaResult r = Umeyama(a, Apply(truth, a));
  ASSERT_TRUE(r.ok()) << UmeyamaFailureName(r.failure);
  EXPECT_NEAR(r.b_from_a->scale, 2.5, 1e-13);
  EXPECT_LT(RotationError(r.b_from_a->rotation, truth.rotation), 1e-14);
  EXPECT_LT((r.b_from_a->translation - truth.translation).norm(), 1e-13);
  EXPECT_LT(r.rms_error, 1e-13);
}

TEST(Umeyama, RigidModeFixesScaleToOne) {
  const Sim3 truth(1, *Theta({0, 0, 1}, -0.4), {1, 2, 3});
  const auto a = Cloud(6, 2, {1, 1, 1}, 2);
  UmeyamaOptions rigid;
  rigid.estimate_scale = false;
  const UmeyamaResult r = Umeyama(a, Apply(truth, a), rigid);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.b_from_a->scale, 1);
  EXPECT_LT(RotationError(r.b_from_a->rotation, truth.rotation), 1e-14);
}

TEST(Umeyama, FewerThanThreePointsFails) {
  std::vector<Eigen::Vector3d> pts = {{0, 0, 0}, {1, 0, 0}};
  EXPECT_EQ(Umeyama(pts, pts).failure, UmeyamaFailure::kTooFewPoints);
  EXPECT_EQ(Umeyama({}, {}).failure, UmeyamaFailure::kTooFewPoints);
  EXPECT_FALSE(Umeyama(pts, pts).b_from_a);
}

TEST(Umeyama, CollinearPointsFail) {
  std::vector<Eigen::Vector3d> line, plane = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0.5}};
  for (int i = 0; i < 4; ++i)
    line.push_back(Eigen::Vector3d(1, 2, 3) + i * Eigen::Vector3d(0.5, -1, 2));
  EXPECT_EQ(Umeyama(line, line).failure, UmeyamaFailure::kCollinearPoints);
  EXPECT_EQ(Umeyama(plane, line).failure, UmeyamaFailure::kCollinearPoints);  // target collinear
  EXPECT_EQ(Umeyama(line, plane).failure, UmeyamaFailure::kCollinearPoints);  // source collinear
  EXPECT_EQ(UmeyamaFailureName(UmeyamaFailure::kCollinearPoints), "collinear_points");
}

TEST(Umeyama, CollinearPointsAllowedGiveMinimalResidual) {
  std::vector<Eigen::Vector3d> line;
  for (int i = 0; i < 5; ++i) line.push_back(i * Eigen::Vector3d(1, 1, 0));
  const Sim3 truth(3, *Theta({0, 1, 0}, 0.5), {1, 0, 0});
  UmeyamaOptions allow;
  allow.allow_collinear = true;
  const UmeyamaResult r = Umeyama(line, Apply(truth, line), allow);
  ASSERT_TRUE(r.ok());
  EXPECT_LT(r.rms_error, 1e-13);
  EXPECT_NEAR(r.b_from_a->scale, 3, 1e-13);
  EXPECT_NEAR(r.b_from_a->rotation.determinant(), 1, 1e-14);
}

TEST(Umeyama, AllPointsEqualFails) {
  std::vector<Eigen::Vector3d> same(5, Eigen::Vector3d(1e4, 2, 3));
  const auto other = Cloud(5, 1, {0, 0, 0}, 3);
  EXPECT_EQ(Umeyama(same, other).failure, UmeyamaFailure::kCoincidentPoints);
  EXPECT_EQ(Umeyama(other, same).failure, UmeyamaFailure::kCoincidentPoints);
}

TEST(Umeyama, NonFiniteInputFails) {
  auto a = Cloud(5, 1, {0, 0, 0}, 4);
  auto b = a;
  b[3].y() = std::numeric_limits<double>::infinity();
  EXPECT_EQ(Umeyama(a, b).failure, UmeyamaFailure::kNonFinite);
  a[0].x() = std::nan("");
  EXPECT_EQ(Umeyama(a, a).failure, UmeyamaFailure::kNonFinite);
}

TEST(Umeyama, BadInputIsACheckError) {
  const auto a = Cloud(5, 1, {0, 0, 0}, 5);
  EXPECT_THROW(Umeyama(a, Cloud(4, 1, {0, 0, 0}, 5)), CheckError);
  UmeyamaOptions bad;
  bad.collinear_tolerance = 1;
  EXPECT_THROW(Umeyama(a, a, bad), CheckError);
}

TEST(Umeyama, CoplanarPointsSucceed) {
  // Points in the plane z = 0: Sigma has rank 2 and the SVD's third axis may come out
  // mirrored; the det correction must still give the true rotation.
  std::vector<Eigen::Vector3d> a;
  for (int i = 0; i < 12; ++i) a.push_back({std::cos(i * 0.7) * (1 + i % 3), std::sin(i * 1.3), 0});
  std::mt19937_64 rng(6);
  for (int trial = 0; trial < 50; ++trial) {
    const Sim3 truth(0.7, RandomRotation(rng), {1, -1, 2});
    const UmeyamaResult r = Umeyama(a, Apply(truth, a));
    ASSERT_TRUE(r.ok());
    EXPECT_LT(RotationError(r.b_from_a->rotation, truth.rotation), 1e-13);
    EXPECT_NEAR(r.b_from_a->scale, 0.7, 1e-13);
  }
}

TEST(Umeyama, ReflectionYieldsTheBestProperRotation) {
  // a: +-3 e_x, +-2 e_y, +-e_z (covariance diag(3, 4/3, 1/3)); b: a mirrored in x.
  // Sigma = diag(-3, 4/3, 1/3) has det(U V^T) = -1, so S = diag(1, 1, -1) flips the axis
  // of least spread: R = diag(-1, 1, -1) (a half turn about y), never the reflection.
  const std::vector<Eigen::Vector3d> a = {{3, 0, 0},  {-3, 0, 0}, {0, 2, 0},
                                          {0, -2, 0}, {0, 0, 1},  {0, 0, -1}};
  std::vector<Eigen::Vector3d> b;
  for (const auto& p : a) b.push_back({-p.x(), p.y(), p.z()});
  UmeyamaOptions rigid;
  rigid.estimate_scale = false;
  const UmeyamaResult r = Umeyama(a, b, rigid);
  ASSERT_TRUE(r.ok());
  EXPECT_LT((r.b_from_a->rotation - Eigen::Vector3d(-1, 1, -1).asDiagonal().toDenseMatrix())
                .cwiseAbs()
                .maxCoeff(),
            1e-15);
  EXPECT_LT(r.b_from_a->translation.norm(), 1e-15);
  // The two points on z are off by 2 each: rms = sqrt(2 * 4 / 6).
  EXPECT_NEAR(r.rms_error, std::sqrt(8.0 / 6.0), 1e-15);
  // With scale: s = tr(D S) / sigma_a^2 = (3 + 4/3 - 1/3) / (3 + 4/3 + 1/3) = 6/7.
  const UmeyamaResult s = Umeyama(a, b);
  ASSERT_TRUE(s.ok());
  EXPECT_NEAR(s.b_from_a->scale, 6.0 / 7.0, 1e-15);
  EXPECT_NEAR(s.b_from_a->rotation.determinant(), 1, 1e-15);
}

TEST(Umeyama, CoordinatesTenThousandMetresFromTheOrigin) {
  // A 1 m cloud near (1e4, -1e4, 1e4) mapped to a frame whose origin is also 1e4 m away.
  // Coordinates there carry rounding of eps * 1e4 ~ 2e-12 m, so over a 1 m spread the
  // rotation is determined to ~1e-12 rad (bound 1e-10) and every point maps to ~1e-11 m.
  const auto a = Cloud(20, 0.5, {1e4, -1e4, 1e4}, 7);
  const Sim3 truth(1, *Theta({0.2, 1, -0.3}, 2.0), {-3e3, 1.2e4, 5e3});
  UmeyamaOptions rigid;
  rigid.estimate_scale = false;
  const UmeyamaResult r = Umeyama(a, Apply(truth, a), rigid);
  ASSERT_TRUE(r.ok());
  EXPECT_LT(RotationError(r.b_from_a->rotation, truth.rotation), 1e-10);
  for (const auto& p : a) EXPECT_LT((*r.b_from_a * p - truth * p).norm(), 1e-9);
  EXPECT_LT(r.rms_error, 1e-10);
  const UmeyamaResult sim = Umeyama(a, Apply(truth, a));
  ASSERT_TRUE(sim.ok());
  EXPECT_NEAR(sim.b_from_a->scale, 1, 1e-10);
}

TEST(Umeyama, ScalesOfOneThousandthAndOneThousand) {
  const auto a = Cloud(8, 1, {0.5, 0, -1}, 8);
  for (double scale : {1e-3, 1e3}) {
    const Sim3 truth(scale, *Theta({1, 1, 1}, 0.9), {2, 0, -1});
    const UmeyamaResult fwd = Umeyama(a, Apply(truth, a));
    ASSERT_TRUE(fwd.ok());
    EXPECT_NEAR(fwd.b_from_a->scale / scale, 1, 1e-13) << scale;
    EXPECT_LT(RotationError(fwd.b_from_a->rotation, truth.rotation), 1e-13) << scale;
    EXPECT_LT((fwd.b_from_a->translation - truth.translation).norm(), 1e-12 * std::max(1.0, scale));
    // And the inverse direction recovers 1 / scale.
    const UmeyamaResult inv = Umeyama(Apply(truth, a), a);
    ASSERT_TRUE(inv.ok());
    EXPECT_NEAR(inv.b_from_a->scale * scale, 1, 1e-13) << scale;
  }
}

// 10^5 random similarities, exact data: the rotation is orthonormal to 1e-12 and the
// transform is recovered to rounding. The data themselves limit the accuracy: the target
// points of spread ~s sit ~|t| from the origin, so their offsets carry a relative rounding
// error of kappa * eps with kappa = (|t| + 3 s) / s (up to 1e4 here, for s = 1e-3 and |t| ~ 10);
// the recovered rotation and scale must be within 20 kappa eps.
TEST(Umeyama, RandomPropertyExactData) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1, 1), log_scale(-3, 3);
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  double worst_orthonormal = 0, worst_rotation = 0, worst_scale = 0;
  std::vector<Eigen::Vector3d> a(4), b(4);
  for (int i = 0; i < 100000; ++i) {
    const Sim3 truth(std::pow(10, log_scale(rng)), RandomRotation(rng),
                     {10 * u(rng), 10 * u(rng), 10 * u(rng)});
    // A tetrahedron with a random but bounded shape: unit edges along the axes, jittered.
    const Eigen::Vector3d base(u(rng), u(rng), u(rng));
    a[0] = base;
    for (int k = 0; k < 3; ++k)
      a[k + 1] = base + Eigen::Vector3d::Unit(k) + 0.2 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    for (int k = 0; k < 4; ++k) b[k] = truth * a[k];
    const UmeyamaResult r = Umeyama(a, b);
    ASSERT_TRUE(r.ok());
    worst_orthonormal = std::max(worst_orthonormal, OrthonormalityError(r.b_from_a->rotation));
    const double kappa = (truth.translation.norm() + 3 * truth.scale) / truth.scale;
    worst_rotation = std::max(worst_rotation,
                              RotationError(r.b_from_a->rotation, truth.rotation) / (kappa * kEps));
    worst_scale =
        std::max(worst_scale, std::abs(r.b_from_a->scale / truth.scale - 1) / (kappa * kEps));
  }
  EXPECT_LT(worst_orthonormal, 1e-12);
  EXPECT_LT(worst_rotation, 20);
  EXPECT_LT(worst_scale, 20);
}

// 10^5 random similarities with Gaussian noise sigma on every target coordinate; the source
// is the cube with corners (+-1, +-1, +-1) (N = 8). First-order least-squares theory:
//  - rotation: the information about a small turn about axis e_k is
//    sum_i |s a_i x e_k|^2 / sigma^2 = 16 s^2 / sigma^2, so each axis component of the
//    rotation error has std sigma / (4 s), and the error angle (the norm of three such
//    components) exceeds 7 sigma / (4 s) with probability P(chi^2_3 > 49) ~ 1e-10;
//  - scale: s_est - s = sum_i n_i . R a_i / sum_i |a_i|^2 has std sigma / sqrt(24);
//    7 std: P ~ 3e-12;
//  - the centroid maps with the mean noise, std sigma / sqrt(8) per axis; 7 such std in
//    norm: P(chi^2_3 > 49) ~ 1e-10.
// Over 10^5 samples the chance that any bound fails is below 1e-4. Higher-order terms are
// O((sigma / s)^2) relative and negligible at sigma / s <= 2e-3.
TEST(Umeyama, RandomPropertyNoiseBoundedByTheory) {
  std::vector<Eigen::Vector3d> a;
  for (int k = 0; k < 8; ++k)
    a.push_back({k & 1 ? 1.0 : -1.0, k & 2 ? 1.0 : -1.0, k & 4 ? 1.0 : -1.0});
  std::mt19937_64 rng(10);
  std::uniform_real_distribution<double> u(-1, 1), scale_dist(0.5, 2);
  const double sigma = 1e-3;
  std::normal_distribution<double> noise(0, sigma);
  std::vector<Eigen::Vector3d> b(8);
  double worst_orthonormal = 0, worst_rotation_ratio = 0, worst_scale_ratio = 0,
         worst_centroid_ratio = 0;
  for (int i = 0; i < 100000; ++i) {
    const Sim3 truth(scale_dist(rng), RandomRotation(rng), {5 * u(rng), 5 * u(rng), 5 * u(rng)});
    for (int k = 0; k < 8; ++k)
      b[k] = truth * a[k] + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    const UmeyamaResult r = Umeyama(a, b);
    ASSERT_TRUE(r.ok());
    const Sim3& est = *r.b_from_a;
    worst_orthonormal = std::max(worst_orthonormal, OrthonormalityError(est.rotation));
    worst_rotation_ratio =
        std::max(worst_rotation_ratio,
                 RotationError(est.rotation, truth.rotation) / (7 * sigma / (4 * truth.scale)));
    worst_scale_ratio = std::max(worst_scale_ratio,
                                 std::abs(est.scale - truth.scale) / (7 * sigma / std::sqrt(24.0)));
    worst_centroid_ratio =
        std::max(worst_centroid_ratio,
                 (est.translation - truth.translation).norm() / (7 * sigma / std::sqrt(8.0)));
  }
  EXPECT_LT(worst_orthonormal, 1e-12);
  EXPECT_LT(worst_rotation_ratio, 1);
  EXPECT_LT(worst_scale_ratio, 1);
  EXPECT_LT(worst_centroid_ratio, 1);  // the cube's centroid is the origin: t maps it
}

}  // namespace
}  // namespace reenact
