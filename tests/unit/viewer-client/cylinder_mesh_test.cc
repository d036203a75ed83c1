#include "viewer-client/render/cylinder_mesh.h"

#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <tuple>
#include <utility>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "common/error/check.h"
#include "common/render/cylinder_mesh.h"

namespace reenact::viewer {
namespace {

Eigen::Vector3d D(const Eigen::Vector3f& v) { return v.cast<double>(); }

TEST(CylinderMesh, SizesFollowTheSegmentCount) {
  for (int n : {3, 8, 32}) {
    const CylinderMesh mesh = MakeUnitCylinderMesh(n);
    EXPECT_EQ(mesh.positions.size(), static_cast<size_t>((kShapeRings + 2 * kCapRings) * n + 2));
    EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
    EXPECT_EQ(mesh.indices.size(),
              static_cast<size_t>(3 * (2 * (kShapeRings - 1) * n + 2 * (2 * kCapRings - 1) * n)));
    for (uint32_t i : mesh.indices) EXPECT_LT(i, mesh.positions.size());
  }
}

TEST(CylinderMesh, VerticesLieOnTheUnitCylinder) {
  const CylinderMesh mesh = MakeUnitCylinderMesh(16);
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const Eigen::Vector3f& p = mesh.positions[i];
    const Eigen::Vector3f& n = mesh.normals[i];
    EXPECT_EQ(p.z() * (kShapeRings - 1), std::round(p.z() * (kShapeRings - 1)));  // on a ring
    EXPECT_TRUE(p.z() >= 0.0f && p.z() <= 1.0f);
    EXPECT_NEAR(n.norm(), 1.0, 1e-6);
    const double r = std::hypot(p.x(), p.y());
    if (n.z() == 0.0f) {  // side: on the mantle, normal radial
      EXPECT_NEAR(r, 1.0, 1e-6);
      EXPECT_NEAR(n.x(), p.x(), 1e-6);
      EXPECT_NEAR(n.y(), p.y(), 1e-6);
    } else {  // cap: normal along the axis, pointing away from the body
      EXPECT_TRUE(p.z() == 0.0f || p.z() == 1.0f);
      bool on_a_cap_ring = false;
      for (int m = 0; m <= kCapRings; ++m) on_a_cap_ring |= std::abs(r - CapRingRadius(m)) < 1e-6;
      EXPECT_TRUE(on_a_cap_ring) << r;
      EXPECT_EQ(n.z(), p.z() == 0.0f ? -1.0f : 1.0f);
    }
  }
}

// Divergence theorem: sum of signed tetrahedra (origin, triangle) is the enclosed volume,
// exactly the prism over the inscribed regular N-gon, area N/2 sin(2 pi / N), height 1.
TEST(CylinderMesh, ClosedOutwardSurfaceEnclosesThePrismVolume) {
  for (int n : {3, 6, 40}) {
    const CylinderMesh mesh = MakeUnitCylinderMesh(n);
    double volume = 0;
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
      const Eigen::Vector3d a = D(mesh.positions[mesh.indices[t]]);
      const Eigen::Vector3d b = D(mesh.positions[mesh.indices[t + 1]]);
      const Eigen::Vector3d c = D(mesh.positions[mesh.indices[t + 2]]);
      volume += a.dot(b.cross(c)) / 6.0;
    }
    EXPECT_NEAR(volume, n / 2.0 * std::sin(2 * std::numbers::pi / n), 1e-5) << n;
  }
}

TEST(CylinderMesh, TrianglesFaceTheirVertexNormals) {
  const CylinderMesh mesh = MakeUnitCylinderMesh(12);
  for (size_t t = 0; t < mesh.indices.size(); t += 3) {
    const Eigen::Vector3d a = D(mesh.positions[mesh.indices[t]]);
    const Eigen::Vector3d b = D(mesh.positions[mesh.indices[t + 1]]);
    const Eigen::Vector3d c = D(mesh.positions[mesh.indices[t + 2]]);
    const Eigen::Vector3d face = (b - a).cross(c - a).normalized();
    for (int k = 0; k < 3; ++k) EXPECT_GT(face.dot(D(mesh.normals[mesh.indices[t + k]])), 0.9);
  }
}

// Watertight: every undirected edge (by position) is used exactly twice, once each way.
TEST(CylinderMesh, EveryEdgeIsSharedByTwoOppositeTriangles) {
  const CylinderMesh mesh = MakeUnitCylinderMesh(10);
  auto key = [&](uint32_t i) {
    const Eigen::Vector3f& p = mesh.positions[i];
    return std::make_tuple(std::lround(p.x() * 1e5), std::lround(p.y() * 1e5),
                           std::lround(p.z() * 1e5));
  };
  std::map<std::pair<decltype(key(0)), decltype(key(0))>, int> directed;
  for (size_t t = 0; t < mesh.indices.size(); t += 3) {
    for (int k = 0; k < 3; ++k) {
      ++directed[{key(mesh.indices[t + k]), key(mesh.indices[t + (k + 1) % 3])}];
    }
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    const auto reverse = directed.find({edge.second, edge.first});
    ASSERT_NE(reverse, directed.end());
    EXPECT_EQ(reverse->second, 1);
  }
}

// The documented order: side vertex k n + i is at angle 2 pi i / n on ring k; band k, quad i
// is triangles 2 (k n + i) and 2 (k n + i) + 1, spanning rings k, k + 1 and angles i, i + 1;
// then (2 kCapRings - 1) n triangles of the z = 0 cap and as many of the z = 1 cap.
TEST(CylinderMesh, VerticesAndTrianglesFollowTheDocumentedOrder) {
  const int n = 7;
  const CylinderMesh mesh = MakeUnitCylinderMesh(n);
  for (int k = 0; k < kShapeRings; ++k)
    for (int i = 0; i < n; ++i) {
      const double angle = 2 * std::numbers::pi * i / n;
      const Eigen::Vector3d expected(std::cos(angle), std::sin(angle),
                                     static_cast<double>(k) / (kShapeRings - 1));
      EXPECT_NEAR((D(mesh.positions[k * n + i]) - expected).norm(), 0, 1e-6) << k << " " << i;
    }
  for (int k = 0; k + 1 < kShapeRings; ++k)
    for (int i = 0; i < n; ++i) {
      for (int half = 0; half < 2; ++half) {
        const size_t t = 2 * static_cast<size_t>(k * n + i) + half;
        for (int v = 0; v < 3; ++v) {
          const uint32_t index = mesh.indices[3 * t + v];
          ASSERT_LT(index, static_cast<uint32_t>(kShapeRings * n));
          const int ring = static_cast<int>(index) / n, at = static_cast<int>(index) % n;
          EXPECT_TRUE(ring == k || ring == k + 1);
          EXPECT_TRUE(at == i || at == (i + 1) % n);
        }
      }
    }
  const int per_cap = (2 * kCapRings - 1) * n;
  for (int cap = 0; cap < 2; ++cap)
    for (int i = 0; i < per_cap; ++i) {
      const size_t t = 2 * static_cast<size_t>((kShapeRings - 1) * n) + cap * per_cap + i;
      for (int v = 0; v < 3; ++v)
        EXPECT_EQ(mesh.positions[mesh.indices[3 * t + v]].z(), static_cast<float>(cap));
    }
}

TEST(CylinderMesh, RingOfAVertexAndRingSlopes) {
  for (int k = 0; k < kShapeRings; ++k)
    EXPECT_EQ(RingOfUnitVertex(static_cast<float>(k) / (kShapeRings - 1)), k);
  EXPECT_EQ(RingOfUnitVertex(-0.3), 0);
  EXPECT_EQ(RingOfUnitVertex(1.7), kShapeRings - 1);
  // A linear profile has its slope everywhere; a zigzag 0 1 0 1 0 has one-sided slopes at the
  // ends (+-1 over a quarter) and zero central differences inside.
  const std::array<double, kShapeRings> linear = {1.0, 1.25, 1.5, 1.75, 2.0};
  const std::array<double, kShapeRings> zigzag = {0, 1, 0, 1, 0};
  for (int k = 0; k < kShapeRings; ++k) EXPECT_NEAR(RingSlope(linear, k), 1.0, 1e-12);
  EXPECT_NEAR(RingSlope(zigzag, 0), 4.0, 1e-12);
  EXPECT_NEAR(RingSlope(zigzag, 2), 0.0, 1e-12);
  EXPECT_NEAR(RingSlope(zigzag, 4), -4.0, 1e-12);
  EXPECT_THROW(RingSlope(zigzag, kShapeRings), CheckError);
}

// Each vertex lands at (width[k] x, depth[k] y, z) of its ring k.
TEST(CylinderMesh, ShapedPositionsScaleEachRingByItsWidthAndDepth) {
  PartShape shape;
  shape.width = {1.0, 1.5, 2.0, 2.5, 3.0};
  shape.depth = {0.5, 0.6, 0.7, 0.8, 0.9};
  const CylinderMesh mesh = MakeUnitCylinderMesh(9);
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const Eigen::Vector3d p = D(mesh.positions[v]);
    const int k = static_cast<int>(std::lround(p.z() * (kShapeRings - 1)));
    const Eigen::Vector3d q = ShapedUnitPosition(shape, p);
    EXPECT_NEAR(q.x(), shape.width[k] * p.x(), 1e-12);
    EXPECT_NEAR(q.y(), shape.depth[k] * p.y(), 1e-12);
    EXPECT_EQ(q.z(), p.z());
    EXPECT_EQ(ShapedUnitPosition(PartShape{}, p), p);  // the plain cylinder is unchanged
  }
}

// Similar polygons 1 -> 2 times the regular n-gon: a frustum of a pyramid, volume
// h / 3 (A0 + A1 + sqrt(A0 A1)) = 7/3 A; an elliptic prism (rings all 1.5 x 0.4): 0.6 A.
TEST(CylinderMesh, ShapedMeshEnclosesTheFrustumAndEllipticPrismVolumes) {
  const int n = 24;
  const double area = n / 2.0 * std::sin(2 * std::numbers::pi / n);
  PartShape cone, elliptic;
  cone.width = cone.depth = {1.0, 1.25, 1.5, 1.75, 2.0};
  elliptic.width.fill(1.5);
  elliptic.depth.fill(0.4);
  const CylinderMesh mesh = MakeUnitCylinderMesh(n);
  for (const auto& [shape, expected] :
       {std::pair{cone, 7.0 / 3.0 * area}, std::pair{elliptic, 0.6 * area}}) {
    double volume = 0;
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
      const Eigen::Vector3d a = ShapedUnitPosition(shape, D(mesh.positions[mesh.indices[t]]));
      const Eigen::Vector3d b = ShapedUnitPosition(shape, D(mesh.positions[mesh.indices[t + 1]]));
      const Eigen::Vector3d c = ShapedUnitPosition(shape, D(mesh.positions[mesh.indices[t + 2]]));
      volume += a.dot(b.cross(c)) / 6.0;
    }
    EXPECT_NEAR(volume, expected, 1e-5);
  }
}

// For linear ring profiles W(z) = W0 + a z, D(z) = D0 + b z the rule's side normal is the exact
// normal of the smooth surface (W(z) cos t, D(z) sin t, z): orthogonal to both tangents
// (-W sin t, D cos t, 0) and (a cos t, b sin t, 1), and pointing outwards.
TEST(CylinderMesh, ShapedSideNormalsAreExactForLinearProfiles) {
  PartShape shape;
  shape.width = {1.0, 1.1, 1.2, 1.3, 1.4};  // a = 0.4
  shape.depth = {0.9, 0.8, 0.7, 0.6, 0.5};  // b = -0.4
  const CylinderMesh mesh = MakeUnitCylinderMesh(16);
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const Eigen::Vector3d p = D(mesh.positions[v]), m = D(mesh.normals[v]);
    const Eigen::Vector3d n = ShapedUnitNormal(shape, p, m);
    if (m.z() != 0) {
      EXPECT_EQ(n, m);  // caps keep their normal
      continue;
    }
    const double c = m.x(), s = m.y(), z = p.z();
    const double w = 1.0 + 0.4 * z, d = 0.9 - 0.4 * z;
    EXPECT_NEAR(n.dot(Eigen::Vector3d(-w * s, d * c, 0)), 0, 1e-6);
    EXPECT_NEAR(n.dot(Eigen::Vector3d(0.4 * c, -0.4 * s, 1)), 0, 1e-6);
    EXPECT_GT(n.dot(Eigen::Vector3d(c, s, 0)), 0);
  }
  // The plain cylinder keeps the radial normal.
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    EXPECT_NEAR((ShapedUnitNormal(PartShape{}, D(mesh.positions[v]), D(mesh.normals[v])) -
                 D(mesh.normals[v]))
                    .norm(),
                0, 1e-12);
}

// A height map scales each vertex by its factor: at the nodes (every 90 degrees for 4 angles)
// by the node's value, half way between two nodes by their mean; caps follow their end ring.
TEST(CylinderMesh, SurfaceScalesEachVertexByTheHeightMap) {
  PartShape shape;
  shape.width = {1.0, 1.1, 1.2, 1.3, 1.4};
  shape.depth = shape.width;
  shape.surface.angles = 4;
  for (int k = 0; k < kShapeRings; ++k) shape.surface.radial[k] = {1.2, 0.8, 1.3, 0.7};
  const CylinderMesh mesh = MakeUnitCylinderMesh(32);
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const Eigen::Vector3d p = D(mesh.positions[v]);
    const double r = p.head<2>().norm();
    if (r < 1e-6) continue;  // a cap's pole
    const int k = RingOfUnitVertex(p.z());
    const double phi = std::atan2(p.y(), p.x());
    const double radius = ShapedUnitPosition(shape, p, D(mesh.normals[v])).head<2>().norm();
    const auto near = [phi](double deg) {
      return std::abs(std::remainder(phi - deg * std::numbers::pi / 180, 2 * std::numbers::pi)) <
             1e-6;
    };
    if (near(0)) {
      EXPECT_NEAR(radius, 1.2 * shape.width[k] * r, 1e-6);
    }
    if (near(90)) {
      EXPECT_NEAR(radius, 0.8 * shape.width[k] * r, 1e-6);
    }
    if (near(180)) {
      EXPECT_NEAR(radius, 1.3 * shape.width[k] * r, 1e-6);
    }
    if (near(-45)) {
      EXPECT_NEAR(radius, 0.95 * shape.width[k] * r, 1e-6);
    }
  }
  EXPECT_FALSE(shape.IsCylinder());
  EXPECT_FALSE(shape.IsCircular());
  EXPECT_NEAR(shape.RingReach(4), 1.3 * 1.4, 1e-12);
}

// Rounded ends (cap_depth h): the closed mesh encloses the prism and two half ellipsoids over
// the end discs, pi r^2 (2/3) h each; the tessellation is inscribed, so a little less.
TEST(CylinderMesh, RoundedEndsEncloseHalfEllipsoids) {
  const int n = 128;
  const double prism = n / 2.0 * std::sin(2 * std::numbers::pi / n);
  PartShape shape;
  shape.cap_depth = {0.3, 0.1};
  EXPECT_FALSE(shape.IsCylinder());
  const CylinderMesh mesh = MakeUnitCylinderMesh(n);
  double volume = 0;
  for (size_t t = 0; t < mesh.indices.size(); t += 3) {
    Eigen::Vector3d p[3];
    for (int k = 0; k < 3; ++k)
      p[k] = ShapedUnitPosition(shape, D(mesh.positions[mesh.indices[t + k]]),
                                D(mesh.normals[mesh.indices[t + k]]));
    volume += p[0].dot(p[1].cross(p[2])) / 6.0;
  }
  const double domes = 2.0 / 3.0 * std::numbers::pi * (0.3 + 0.1);
  EXPECT_LT(volume, prism + domes);
  EXPECT_GT(volume, prism + 0.9 * domes);
}

// Placed as a body part (radius 0.1 m, length 0.5 m, elliptic and tapered), every triangle
// faces its vertices' normals (NormalFromUnitCylinder of ShapedUnitNormal); with a height map
// and rounded ends as well, where the faces of a surface whose factor swings by up to 0.3
// between neighbouring nodes and rings lean up to about 40 degrees from the smooth normal.
TEST(CylinderMesh, ShapedTrianglesFaceTheirVertexNormals) {
  PartShape shape;
  shape.width = {1.4, 1.5, 1.6, 1.4, 1.2};
  shape.depth = {0.8, 0.9, 1.0, 0.9, 0.7};
  PartShape surface = shape;
  surface.surface.angles = 8;
  for (int k = 0; k < kShapeRings; ++k)
    for (int j = 0; j < 8; ++j)
      surface.surface.radial[k][j] = 1 + 0.15 * std::cos(2 * std::numbers::pi * j / 4 + k);
  surface.cap_depth = {0.2, 0.1};
  const CylinderMesh mesh = MakeUnitCylinderMesh(kDefaultCylinderSegments);
  for (const auto& [shaped, least] : {std::pair{shape, 0.95}, std::pair{surface, 0.7}}) {
    const Eigen::Matrix4d m =
        ViewerFromUnitCylinder(Eigen::Vector3d(0.1, 0.2, 2.0), Eigen::Vector3d(0.3, 0.6, 2.2), 0.1,
                               Eigen::Vector3d(1, 0, 0));
    const Eigen::Matrix3d normal_from_cylinder = NormalFromUnitCylinder(m);
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
      Eigen::Vector3d p[3], n[3];
      for (int k = 0; k < 3; ++k) {
        const uint32_t i = mesh.indices[t + k];
        p[k] = m.topLeftCorner<3, 3>() *
               ShapedUnitPosition(shaped, D(mesh.positions[i]), D(mesh.normals[i]));
        n[k] = (normal_from_cylinder *
                ShapedUnitNormal(shaped, D(mesh.positions[i]), D(mesh.normals[i])))
                   .normalized();
      }
      const Eigen::Vector3d face = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
      for (int k = 0; k < 3; ++k) EXPECT_GT(face.dot(n[k]), least) << t;
    }
  }
}

// x_hat follows the width direction made orthogonal to the axis; y_hat = z_hat x x_hat; without
// a usable direction (none, zero, along the axis) the helper rule.
TEST(ViewerFromUnitCylinder, WidthDirectionSetsTheFrameElseTheHelperRule) {
  const Eigen::Vector3d a(0.1, -0.2, 2.0), b(0.1, 0.4, 2.1);
  const double r = 0.15;
  const Eigen::Vector3d z = (b - a).normalized();
  const Eigen::Vector3d w(1.0, 0.3, 0.2);  // not orthogonal to the axis
  const Eigen::Matrix4d m = ViewerFromUnitCylinder(a, b, r, w);
  const Eigen::Vector3d expected_x = (w - w.dot(z) * z).normalized();
  EXPECT_NEAR((m.block<3, 1>(0, 0) - r * expected_x).norm(), 0, 1e-12);
  EXPECT_NEAR((m.block<3, 1>(0, 1) - r * z.cross(expected_x)).norm(), 0, 1e-12);
  EXPECT_NEAR((m.block<3, 1>(0, 2) - (b - a)).norm(), 0, 1e-12);
  EXPECT_NEAR((m.block<3, 1>(0, 3) - a).norm(), 0, 1e-12);
  const Eigen::Matrix3d linear = m.topLeftCorner<3, 3>();
  EXPECT_GT(linear.determinant(), 0);

  const Eigen::Matrix4d helper = ViewerFromUnitCylinder(a, b, r);
  const Eigen::Vector3d helper_x = z.cross(Eigen::Vector3d::UnitX()).normalized();  // |z.x| < 0.9
  EXPECT_NEAR((helper.block<3, 1>(0, 0) - r * helper_x).norm(), 0, 1e-12);
  EXPECT_EQ(ViewerFromUnitCylinder(a, b, r, Eigen::Vector3d::Zero()), helper);
  EXPECT_EQ(ViewerFromUnitCylinder(a, b, r, Eigen::Vector3d(3 * (b - a))), helper);
  EXPECT_EQ(ViewerFromUnitCylinder(a, b, r, std::nullopt), helper);
  EXPECT_TRUE(ViewerFromUnitCylinder(a, b, r, Eigen::Vector3d(1e-300, 0, 0)).allFinite());

  Cylinder cylinder{a, b, r};
  cylinder.width_direction = w;
  EXPECT_EQ(ViewerFromUnitCylinder(cylinder), m);
}

TEST(ViewerFromUnitCylinder, NormalMatrixIsTheInverseTranspose) {
  const Eigen::Matrix4d m =
      ViewerFromUnitCylinder(Eigen::Vector3d(0.3, 0.1, 1.5), Eigen::Vector3d(-0.2, 0.5, 1.9), 0.07,
                             Eigen::Vector3d(0, 0, 1));
  const Eigen::Matrix3d n = NormalFromUnitCylinder(m);
  EXPECT_NEAR((m.topLeftCorner<3, 3>().transpose() * n - Eigen::Matrix3d::Identity()).norm(), 0,
              1e-12);
}

TEST(CylinderMesh, RejectsFewerThanThreeSegments) {
  EXPECT_THROW(MakeUnitCylinderMesh(2), CheckError);
}

}  // namespace
}  // namespace reenact::viewer
