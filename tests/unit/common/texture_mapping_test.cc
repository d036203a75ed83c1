#include "common/texture/texture_mapping.h"

#include <cmath>
#include <ostream>
#include <string>

#include <gtest/gtest.h>

namespace reenact {
namespace {

// A point on the cylinder (a, b, radius) at height fraction h and angle phi from the side
// facing the origin, built from the cylinder's definition alone (independent of the code).
Eigen::Vector3d PointOnCylinder(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius,
                                double h, double phi) {
  const Eigen::Vector3d u = (b - a).normalized();
  const Eigen::Vector3d mid = 0.5 * (a + b);
  Eigen::Vector3d f = -mid - (-mid).dot(u) * u;
  f.normalize();
  const Eigen::Vector3d side = u.cross(f);
  return a + h * (b - a) + radius * (std::cos(phi) * f + std::sin(phi) * side);
}

Eigen::Vector3d Apply(const Eigen::Matrix4d& m, const Eigen::Vector3d& p) {
  return m.topLeftCorner<3, 3>() * p + m.topRightCorner<3, 1>();
}

struct CylinderPair {
  const char* name;
  Eigen::Vector3d a_viewer, b_viewer, a_stored, b_stored;
};

void PrintTo(const CylinderPair& c, std::ostream* os) { *os << c.name; }

class MappingOnSyntheticCylinders : public ::testing::TestWithParam<CylinderPair> {};

TEST_P(MappingOnSyntheticCylinders, PointLandsOnSameHeightAndAngle) {
  const CylinderPair& c = GetParam();
  const double ratio = 0.2;
  const double rv = ratio * (c.b_viewer - c.a_viewer).norm();
  const double rs = ratio * (c.b_stored - c.a_stored).norm();
  const auto m = StoredFromViewerMapping(c.a_viewer, c.b_viewer, c.a_stored, c.b_stored);
  ASSERT_TRUE(m);
  for (double h : {0.0, 0.3, 1.0})
    for (double phi : {0.0, 0.8, -1.9, M_PI}) {
      const Eigen::Vector3d p_viewer = PointOnCylinder(c.a_viewer, c.b_viewer, rv, h, phi);
      const Eigen::Vector3d expected = PointOnCylinder(c.a_stored, c.b_stored, rs, h, phi);
      EXPECT_LT((Apply(*m, p_viewer) - expected).norm(), 1e-9) << "h=" << h << " phi=" << phi;
    }
}

INSTANTIATE_TEST_SUITE_P(
    Poses, MappingOnSyntheticCylinders,
    ::testing::Values(
        // Same cylinder: identity.
        CylinderPair{"same", {0.1, -0.2, 2.5}, {0.1, 0.3, 2.5}, {0.1, -0.2, 2.5}, {0.1, 0.3, 2.5}},
        // Stored arm longer, rotated and moved.
        CylinderPair{"moved", {0.2, -0.1, 2.0}, {0.5, 0.0, 2.1}, {-0.3, 0.2, 3.0}, {-0.3, 0.6, 3.3}},
        // Anti-parallel axes (the cross product of Eq. 8 vanishes, angle pi).
        CylinderPair{"antiparallel", {0, -0.3, 2.0}, {0, 0.3, 2.0}, {0.2, 0.25, 2.4}, {0.2, -0.35, 2.4}},
        // Parallel axes, different facing (stored seen from the side).
        CylinderPair{"parallel_side_view", {0, 0, 2.0}, {0, 0.4, 2.0}, {1.5, 0, 0.5}, {1.5, 0.4, 0.5}}),
    [](const ::testing::TestParamInfo<CylinderPair>& info) { return std::string(info.param.name); });

TEST(FacingDirection, PointsTowardsCameraAndIsOrthogonalToAxis) {
  const auto f = FacingDirection({0.5, -0.5, 2}, {0.5, 0.5, 2});
  ASSERT_TRUE(f);
  EXPECT_LT((*f - Eigen::Vector3d(-0.5, 0, -2).normalized()).norm(), 1e-12);
}

TEST(FacingDirection, CameraOnAxisLineGivesDefinedOrthogonalUnitVector) {
  const auto f = FacingDirection({0, 0, 1}, {0, 0, 2});
  ASSERT_TRUE(f);
  EXPECT_NEAR(f->norm(), 1.0, 1e-12);
  EXPECT_NEAR(f->z(), 0.0, 1e-12);
}

TEST(FacingDirection, ZeroLengthAxisFails) {
  EXPECT_FALSE(FacingDirection({1, 2, 3}, {1, 2, 3}));
  EXPECT_FALSE(StoredFromViewerMapping({0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 1, 1}));
  EXPECT_FALSE(StoredFromViewerMapping({0, 0, 1}, {0, 1, 1}, {0, 0, 1}, {0, 0, 1}));
}

TEST(FacingDirection, NonFiniteInputFails) {
  EXPECT_FALSE(FacingDirection({std::nan(""), 0, 1}, {0, 0, 1}));
}

}  // namespace
}  // namespace reenact
