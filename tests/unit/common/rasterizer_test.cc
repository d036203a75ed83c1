#include "common/render/rasterizer.h"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "common/error/check.h"

namespace reenact {
namespace {

PinholeCamera SmallCamera() {
  PinholeCamera c;
  c.width = 64;
  c.height = 48;
  c.fx = 100;
  c.fy = 110;
  c.cx = 32.25;
  c.cy = 23.5;
  return c;
}

// The camera-frame point at depth z that projects to pixel (u, v).
Eigen::Vector3d AtPixel(const PinholeCamera& c, double u, double v, double z) {
  return {(u - c.cx) / c.fx * z, (v - c.cy) / c.fy * z, z};
}

RasterVertex Vertex(const Eigen::Vector3d& p) {
  RasterVertex v;
  v.position = p;
  for (int k = 0; k < 3; ++k) v.attributes[k] = static_cast<float>(p[k]);
  return v;
}

// Draws a fronto-parallel quad (two triangles sharing a diagonal) whose corners project to
// [u0, u1] x [v0, v1] and counts how often each pixel was shaded.
Image<int> DrawQuadCounts(const PinholeCamera& c, double u0, double u1, double v0, double v1,
                          double z) {
  RasterOptions options;
  options.depth_test = false;
  Rasterizer r(c, options);
  Image<int> count(c.width, c.height, 1, 0);
  const RasterVertex p00 = Vertex(AtPixel(c, u0, v0, z)), p10 = Vertex(AtPixel(c, u1, v0, z));
  const RasterVertex p01 = Vertex(AtPixel(c, u0, v1, z)), p11 = Vertex(AtPixel(c, u1, v1, z));
  auto shader = [&](const RasterFragment& f) {
    EXPECT_NEAR(f.depth, z, 1e-9);
    ++count.at(f.x, f.y);
    return true;
  };
  r.DrawTriangle(p00, p10, p11, 0, shader);
  r.DrawTriangle(p00, p11, p01, 1, shader);
  return count;
}

TEST(Rasterizer, QuadCoversExactlyTheEnclosedPixelCentres) {
  const PinholeCamera c = SmallCamera();
  const Image<int> count = DrawQuadCounts(c, 10.3, 20.7, 5.2, 15.9, 2.0);
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      const bool inside = x >= 11 && x <= 20 && y >= 6 && y <= 15;
      EXPECT_EQ(count.at(x, y), inside ? 1 : 0) << x << "," << y;
    }
}

TEST(Rasterizer, TopLeftRuleOnPixelAlignedQuad) {
  // Corners on pixel centres: left and top edges own their pixels, right and bottom do not,
  // so a 10 x 10 pixel quad covers exactly 100 pixels.
  const PinholeCamera c = SmallCamera();
  const Image<int> count = DrawQuadCounts(c, 10, 20, 5, 15, 3.0);
  int total = 0;
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      const bool inside = x >= 10 && x < 20 && y >= 5 && y < 15;
      EXPECT_EQ(count.at(x, y), inside ? 1 : 0) << x << "," << y;
      total += count.at(x, y);
    }
  EXPECT_EQ(total, 100);
}

TEST(Rasterizer, SharedEdgesOfATriangulatedPlaneDrawEveryPixelOnce) {
  // A jittered grid over more than the whole image, split into triangles along alternating
  // diagonals, at varying depth: every pixel centre lies in exactly one triangle.
  const PinholeCamera c = SmallCamera();
  RasterOptions options;
  options.depth_test = false;
  Rasterizer r(c, options);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-2.3, 2.3);
  const int n = 9;
  std::vector<RasterVertex> vertices;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const bool border = i == 0 || j == 0 || i == n || j == n;
      const double u = -5 + i * (c.width + 10.0) / n + (border ? 0 : jitter(rng));
      const double v = -5 + j * (c.height + 10.0) / n + (border ? 0 : jitter(rng));
      vertices.push_back(Vertex(AtPixel(c, u, v, 1.5 + 0.1 * i + 0.05 * j)));
    }
  std::vector<Eigen::Vector3i> triangles;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, d = a + n + 1, e = d + 1;
      if ((i + j) % 2 == 0) {
        triangles.emplace_back(a, b, e);
        triangles.emplace_back(a, e, d);
      } else {
        triangles.emplace_back(a, b, d);
        triangles.emplace_back(b, e, d);
      }
    }
  Image<int> count(c.width, c.height, 1, 0);
  r.DrawMesh(vertices, triangles, {}, [&](const RasterFragment& f) {
    ++count.at(f.x, f.y);
    return true;
  });
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) EXPECT_EQ(count.at(x, y), 1) << x << "," << y;
}

TEST(Rasterizer, InterpolationIsPerspectiveCorrect) {
  // A strongly tilted plane; the attributes are the vertices' own 3D coordinates, so at each
  // pixel they must equal the ray-plane intersection, and so must the depth.
  const PinholeCamera c = SmallCamera();
  Rasterizer r(c);
  const Eigen::Vector3d a(-1.0, -0.6, 1.0), b(1.2, -0.5, 6.0), d(-0.4, 0.9, 4.0);
  const Eigen::Vector3d normal = (b - a).cross(d - a);
  int shaded = 0;
  r.DrawTriangle(Vertex(a), Vertex(b), Vertex(d), 0, [&](const RasterFragment& f) {
    const Eigen::Vector3d ray((f.x - c.cx) / c.fx, (f.y - c.cy) / c.fy, 1.0);
    const double t = normal.dot(a) / normal.dot(ray);
    const Eigen::Vector3d hit = t * ray;
    EXPECT_NEAR(f.depth, hit.z(), 1e-3 * hit.z());
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(f.attributes[k], hit[k], 2e-3 * hit.z());
    ++shaded;
    return true;
  });
  EXPECT_GT(shaded, 200);
}

TEST(Rasterizer, CloserSurfaceWinsInEitherDrawingOrder) {
  const PinholeCamera c = SmallCamera();
  for (bool near_first : {true, false}) {
    Rasterizer r(c);
    Image<int> id(c.width, c.height, 1, -1);
    auto shader = [&](const RasterFragment& f) {
      id.at(f.x, f.y) = f.primitive_id;
      return true;
    };
    auto quad = [&](double u0, double u1, double z, int pid) {
      r.DrawTriangle(Vertex(AtPixel(c, u0, 4.5, z)), Vertex(AtPixel(c, u1, 4.5, z)),
                     Vertex(AtPixel(c, u1, 40.5, z)), pid, shader);
      r.DrawTriangle(Vertex(AtPixel(c, u0, 4.5, z)), Vertex(AtPixel(c, u1, 40.5, z)),
                     Vertex(AtPixel(c, u0, 40.5, z)), pid, shader);
    };
    if (near_first) {
      quad(20.5, 50.5, 2.0, 7);
      quad(5.5, 35.5, 3.0, 9);
    } else {
      quad(5.5, 35.5, 3.0, 9);
      quad(20.5, 50.5, 2.0, 7);
    }
    for (int x = 6; x <= 35; ++x) {
      const int expected = x >= 21 ? 7 : 9;
      EXPECT_EQ(id.at(x, 20), expected) << x;
      EXPECT_DOUBLE_EQ(r.depth().at(x, 20), expected == 7 ? 2.0 : 3.0);
    }
    EXPECT_EQ(id.at(45, 20), 7);
    EXPECT_TRUE(std::isinf(r.depth().at(2, 20)));
  }
}

TEST(Rasterizer, TriangleCrossingTheCameraPlaneIsClippedAtNear) {
  // A floor y = 1 (y down: one metre below the camera) reaching from 5 m behind the camera
  // to 10 m ahead. Every pixel whose ray meets the triangle in front of the near plane is
  // drawn with the ray's depth; no other pixel is.
  PinholeCamera c = SmallCamera();
  RasterOptions options;
  options.near_z = 0.2;
  Rasterizer r(c, options);
  const Eigen::Vector2d p0(-3, -5), p1(4, -4), p2(0.5, 10);  // (x, z) on the floor
  Image<double> drawn(c.width, c.height, 1, 0);
  r.DrawTriangle(Vertex({p0.x(), 1, p0.y()}), Vertex({p1.x(), 1, p1.y()}),
                 Vertex({p2.x(), 1, p2.y()}), 0, [&](const RasterFragment& f) {
                   drawn.at(f.x, f.y) = f.depth;
                   return true;
                 });
  int checked = 0, covered = 0;
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      const double dy = (y - c.cy) / c.fy;
      bool inside = false;
      double margin = 1;
      double z = 0;
      if (dy > 0) {
        z = 1 / dy;
        const Eigen::Vector2d q((x - c.cx) / c.fx * z, z);
        const Eigen::Vector2d e0 = p1 - p0, e1 = p2 - p0, w = q - p0;
        const double det = e0.x() * e1.y() - e0.y() * e1.x();
        const double l1 = (w.x() * e1.y() - w.y() * e1.x()) / det;
        const double l2 = (e0.x() * w.y() - e0.y() * w.x()) / det;
        margin = std::min({l1, l2, 1 - l1 - l2, (z - options.near_z) / z});
        inside = margin > 0;
      }
      if (std::abs(margin) < 0.01) continue;  // within snapping distance of an edge
      ++checked;
      EXPECT_EQ(drawn.at(x, y) > 0, inside) << x << "," << y;
      if (inside) {
        ++covered;
        EXPECT_NEAR(drawn.at(x, y), z, 1e-3 * z);
      }
    }
  EXPECT_GT(covered, 300);
  EXPECT_GT(checked, c.width * c.height / 2);
}

TEST(Rasterizer, TriangleBehindTheCameraDrawsNothing) {
  Rasterizer r(SmallCamera());
  int shaded = 0;
  r.DrawTriangle(Vertex({-1, -1, -2}), Vertex({1, -1, -2}), Vertex({0, 1, -0.001}), 0,
                 [&](const RasterFragment&) { return ++shaded, true; });
  EXPECT_EQ(shaded, 0);
}

TEST(Rasterizer, DegenerateTrianglesDrawNothing) {
  Rasterizer r(SmallCamera());
  int shaded = 0;
  auto shader = [&](const RasterFragment&) { return ++shaded, true; };
  const Eigen::Vector3d a(-0.5, -0.5, 2), b(0.5, 0.4, 2), m = 0.5 * (a + b);
  r.DrawTriangle(Vertex(a), Vertex(b), Vertex(m), 0, shader);  // collinear
  r.DrawTriangle(Vertex(a), Vertex(a), Vertex(b), 0, shader);  // repeated vertex
  // A plane through the camera centre is seen edge-on.
  r.DrawTriangle(Vertex({0, -1, 1}), Vertex({0, 1, 1}), Vertex({0, 0, 3}), 0, shader);
  EXPECT_EQ(shaded, 0);
}

TEST(Rasterizer, CullingAndFacing) {
  const PinholeCamera c = SmallCamera();
  const Eigen::Vector3d a = AtPixel(c, 10, 10, 2), b = AtPixel(c, 30, 10, 2),
                        d = AtPixel(c, 10, 30, 2);
  // Normal (b - a) x (d - a) = (+x) x (+y) = +z points away from the camera: back-facing.
  for (CullMode cull : {CullMode::kNone, CullMode::kBack, CullMode::kFront}) {
    RasterOptions options;
    options.cull = cull;
    options.depth_test = false;  // both windings cover the same pixels
    Rasterizer r(c, options);
    int back = 0, front = 0;
    auto shader = [&](const RasterFragment& f) { return ++(f.front_facing ? front : back), true; };
    r.DrawTriangle(Vertex(a), Vertex(b), Vertex(d), 0, shader);
    r.DrawTriangle(Vertex(a), Vertex(d), Vertex(b), 1, shader);
    EXPECT_EQ(back > 0, cull != CullMode::kBack);
    EXPECT_EQ(front > 0, cull != CullMode::kFront);
    if (cull == CullMode::kNone) {
      EXPECT_EQ(back, front);
    }
  }
}

TEST(Rasterizer, DiscardedFragmentsLeaveTheDepthBuffer) {
  const PinholeCamera c = SmallCamera();
  Rasterizer r(c);
  r.DrawTriangle(Vertex(AtPixel(c, 0, 0, 2)), Vertex(AtPixel(c, 60, 0, 2)),
                 Vertex(AtPixel(c, 0, 45, 2)), 0,
                 [](const RasterFragment& f) { return f.x % 2 == 0; });
  EXPECT_DOUBLE_EQ(r.depth().at(4, 4), 2.0);
  EXPECT_TRUE(std::isinf(r.depth().at(5, 4)));
  r.Clear();
  EXPECT_TRUE(std::isinf(r.depth().at(4, 4)));
}

TEST(Rasterizer, FarPlaneClips) {
  const PinholeCamera c = SmallCamera();
  RasterOptions options;
  options.far_z = 4;
  Rasterizer r(c, options);
  double max_depth = 0;
  int shaded = 0;
  r.DrawTriangle(Vertex({-1, 0.5, 1}), Vertex({1, 0.5, 1}), Vertex({0, 0.5, 9}), 0,
                 [&](const RasterFragment& f) {
                   max_depth = std::max(max_depth, f.depth);
                   return ++shaded, true;
                 });
  EXPECT_GT(shaded, 0);
  EXPECT_LE(max_depth, 4.0);
  EXPECT_GT(max_depth, 3.5);
}

TEST(Rasterizer, BadInputIsRejected) {
  PinholeCamera distorted = SmallCamera();
  distorted.distortion.k1 = 0.1;
  EXPECT_THROW(Rasterizer{distorted}, CheckError);
  RasterOptions bad_near;
  bad_near.near_z = 0;
  EXPECT_THROW(Rasterizer(SmallCamera(), bad_near), CheckError);
  RasterOptions bad_count;
  bad_count.attribute_count = 9;
  EXPECT_THROW(bad_count.Check(), CheckError);

  Rasterizer r(SmallCamera());
  auto shader = [](const RasterFragment&) { return true; };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(r.DrawTriangle(Vertex({0, 0, 1}), Vertex({1, 0, 1}), Vertex({0, nan, 1}), 0, shader),
               CheckError);
  const std::vector<RasterVertex> vertices = {Vertex({0, 0, 1}), Vertex({1, 0, 1})};
  const std::vector<Eigen::Vector3i> triangles = {Eigen::Vector3i(0, 1, 2)};
  EXPECT_THROW(r.DrawMesh(vertices, triangles, {}, shader), CheckError);
}

}  // namespace
}  // namespace reenact
