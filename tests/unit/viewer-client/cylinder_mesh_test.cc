#include "viewer-client/render/cylinder_mesh.h"

#include <cmath>
#include <map>
#include <numbers>
#include <tuple>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "common/error/check.h"

namespace reenact::viewer {
namespace {

Eigen::Vector3d D(const Eigen::Vector3f& v) { return v.cast<double>(); }

TEST(CylinderMesh, SizesFollowTheSegmentCount) {
  for (int n : {3, 8, 32}) {
    const CylinderMesh mesh = MakeUnitCylinderMesh(n);
    EXPECT_EQ(mesh.positions.size(), static_cast<size_t>(4 * n + 2));
    EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
    EXPECT_EQ(mesh.indices.size(), static_cast<size_t>(3 * 4 * n));
    for (uint32_t i : mesh.indices) EXPECT_LT(i, mesh.positions.size());
  }
}

TEST(CylinderMesh, VerticesLieOnTheUnitCylinder) {
  const CylinderMesh mesh = MakeUnitCylinderMesh(16);
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const Eigen::Vector3f& p = mesh.positions[i];
    const Eigen::Vector3f& n = mesh.normals[i];
    EXPECT_TRUE(p.z() == 0.0f || p.z() == 1.0f);
    EXPECT_NEAR(n.norm(), 1.0, 1e-6);
    const double r = std::hypot(p.x(), p.y());
    if (n.z() == 0.0f) {  // side: on the mantle, normal radial
      EXPECT_NEAR(r, 1.0, 1e-6);
      EXPECT_NEAR(n.x(), p.x(), 1e-6);
      EXPECT_NEAR(n.y(), p.y(), 1e-6);
    } else {  // cap: normal along the axis, pointing away from the body
      EXPECT_TRUE(r < 1e-6 || std::abs(r - 1.0) < 1e-6);
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

TEST(CylinderMesh, RejectsFewerThanThreeSegments) {
  EXPECT_THROW(MakeUnitCylinderMesh(2), CheckError);
}

}  // namespace
}  // namespace reenact::viewer
