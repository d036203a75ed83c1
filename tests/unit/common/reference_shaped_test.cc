// The CPU reference renderer drawing shaped cylinders (cylinder_model.h's PartShape: radius
// rings, elliptic cross-sections along a width direction): silhouettes and shading against
// the geometry of the shapes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "common/error/check.h"
#include "common/render/reference_renderer.h"
#include "tests/unit/common/test_part_shapes.h"

namespace reenact {
namespace {

using testing::Cone;
using testing::Uniform;

// Principal point off the pixel grid, to catch half-pixel errors.
PinholeCamera Camera() { return PinholeCamera{160, 120, 200, 200, 80.3, 60.7, {}}; }

ReferencePart Part(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius,
                   const PartShape& shape,
                   const std::optional<Eigen::Vector3d>& width_direction = std::nullopt) {
  ReferencePart part;
  part.cylinder = Cylinder{a, b, radius, shape, width_direction};
  return part;
}

ReferenceRender Render(const ReferencePart& part) {
  const std::vector<ReferencePart> parts = {part};
  return RenderReference(Camera(), parts);
}

// First and last covered pixel along a row (dx = 1) or a column; -1 if none.
std::pair<int, int> Extent(const ReferenceRender& r, int fixed, bool along_row) {
  int first = -1, last = -1;
  const int n = along_row ? r.mask.width : r.mask.height;
  for (int i = 0; i < n; ++i) {
    if (r.mask.at(along_row ? i : fixed, along_row ? fixed : i) == 0) continue;
    if (first < 0) first = i;
    last = i;
  }
  return {first, last};
}

// An elliptic prism along the image's y axis at depth d, semi-axes W r along the width
// direction and D r along axis x width, seen side-on: in rows through its middle the covered
// columns are those between the extreme projections of its tessellated cross-section
// (vertex i at angle 2 pi i / n of ViewerFromUnitCylinder's frame), and that span is the
// analytic silhouette of the ellipse, half-width fx A / sqrt(d^2 - B^2) with A the semi-axis
// across the view and B the one along it, within the tessellation's error.
TEST(ReferenceShaped, EllipticPrismSideOnIsWideAlongItsWidthDirection) {
  const PinholeCamera cam = Camera();
  const double r = 0.1, d = 2.0, w = 1.5, dp = 0.6;
  const Eigen::Vector3d a(0, -0.3, d), b(0, 0.3, d);
  struct Case {
    Eigen::Vector3d width_direction;
    double across, along;  // semi-axes across and along the view, metres
  };
  for (const Case& c : {Case{Eigen::Vector3d::UnitX(), w * r, dp * r},
                        Case{Eigen::Vector3d(0.3, 0, 1).normalized(), 0, 0},
                        Case{Eigen::Vector3d::UnitZ(), dp * r, w * r}}) {
    const ReferenceRender out = Render(Part(a, b, r, Uniform(w, dp), c.width_direction));
    // The frame: x_hat the width direction (orthogonal to y already), y_hat = y x x_hat.
    const Eigen::Vector3d x_hat = c.width_direction;
    const Eigen::Vector3d y_hat = Eigen::Vector3d::UnitY().cross(x_hat);
    double u_min = 1e9, u_max = -1e9;
    for (int i = 0; i < kDefaultCylinderSegments; ++i) {
      const double angle = 2 * std::numbers::pi * i / kDefaultCylinderSegments;
      const Eigen::Vector3d p = Eigen::Vector3d(0, 0, d) +
                                r * (w * std::cos(angle) * x_hat + dp * std::sin(angle) * y_hat);
      u_min = std::min(u_min, cam.fx * p.x() / p.z() + cam.cx);
      u_max = std::max(u_max, cam.fx * p.x() / p.z() + cam.cx);
    }
    for (int row : {45, 55, 61, 70, 80}) {
      const auto [left, right] = Extent(out, row, /*along_row=*/true);
      EXPECT_EQ(left, static_cast<int>(std::ceil(u_min))) << row;
      EXPECT_EQ(right, static_cast<int>(std::floor(u_max))) << row;
      if (c.across > 0) {
        const double half = cam.fx * c.across / std::sqrt(d * d - c.along * c.along);
        EXPECT_NEAR(0.5 * (right - left + 1), half, 1.0) << row;
      }
    }
  }
}

// Seen end-on (axis along the optical axis), the near cap is the ellipse with semi-axes
// fx W r / z and fx D r / z pixels along the width direction and across it.
TEST(ReferenceShaped, EllipticPrismEndOnShowsItsEllipticCap) {
  const PinholeCamera cam = Camera();
  const double r = 0.15, w = 1.4, dp = 0.6;
  const Eigen::Vector3d a(0.02, -0.01, 1.0), b(0.02, -0.01, 1.5);
  const double cu = cam.fx * a.x() / a.z() + cam.cx, cv = cam.fy * a.y() / a.z() + cam.cy;
  const int row = static_cast<int>(std::lround(cv)), column = static_cast<int>(std::lround(cu));
  for (bool width_along_x : {true, false}) {
    const Eigen::Vector3d direction =
        width_along_x ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    const ReferenceRender out = Render(Part(a, b, r, Uniform(w, dp), direction));
    const double half_u = cam.fx * (width_along_x ? w : dp) * r / a.z();
    const double half_v = cam.fy * (width_along_x ? dp : w) * r / a.z();
    const auto [left, right] = Extent(out, row, true);
    const auto [top, bottom] = Extent(out, column, false);
    EXPECT_NEAR(left, cu - half_u, 1.0);
    EXPECT_NEAR(right, cu + half_u, 1.0);
    EXPECT_NEAR(top, cv - half_v, 1.0);
    EXPECT_NEAR(bottom, cv + half_v, 1.0);
    EXPECT_NEAR(out.depth.at(column, row), a.z(), 1e-9);  // the near cap's plane
  }
}

// A cone frustum across the view (axis along x at depth d, rings growing 1 -> 2 from a to b):
// in each column the covered rows are the silhouette of the smooth cone, the largest
// |y| / z over its points in that column's plane x = k z, k = (u - cx) / fx, within a pixel;
// so the half-height grows linearly along the axis, at fy r (to - from) / (fx L) px per
// column.
TEST(ReferenceShaped, ConeSilhouetteWidensLinearlyAlongTheAxis) {
  const PinholeCamera cam = Camera();
  const double r = 0.1, d = 2.0, x0 = -0.3, x1 = 0.3;
  const ReferenceRender out =
      Render(Part(Eigen::Vector3d(x0, 0, d), Eigen::Vector3d(x1, 0, d), r, Cone(1, 2)));
  double sum_u = 0, sum_h = 0, sum_uu = 0, sum_uh = 0;
  int columns = 0;
  for (int u = 56; u <= 104; ++u) {
    const double k = (u - cam.cx) / cam.fx;
    double best = 0;  // max |y| / z over the cone's points in the plane x = k z
    for (int i = 0; i <= 20000; ++i) {
      const double z = d - 0.25 + 0.5 * i / 20000.0;
      const double radius = r * (1 + (k * z - x0) / (x1 - x0));
      const double y2 = radius * radius - (z - d) * (z - d);
      if (y2 > 0) best = std::max(best, std::sqrt(y2) / z);
    }
    const int expected_top = static_cast<int>(std::ceil(cam.cy - cam.fy * best));
    const int expected_bottom = static_cast<int>(std::floor(cam.cy + cam.fy * best));
    const auto [top, bottom] = Extent(out, u, false);
    EXPECT_NEAR(top, expected_top, 1) << u;
    EXPECT_NEAR(bottom, expected_bottom, 1) << u;
    const double h = 0.5 * (bottom - top + 1);
    sum_u += u;
    sum_h += h;
    sum_uu += u * u;
    sum_uh += u * h;
    ++columns;
  }
  const double slope = (columns * sum_uh - sum_u * sum_h) / (columns * sum_uu - sum_u * sum_u);
  EXPECT_NEAR(slope, cam.fy * r * (2 - 1) / (cam.fx * (x1 - x0)), 0.01);
}

// Untextured shading uses the shaped surface's normal: on a steep cone (radius 0.05 -> 0.25 m
// over 0.4 m, slope 0.5) the normal leans back along the axis by atan(0.5), so the two-sided
// Lambert term at a pixel is 0.35 + 0.65 |n . e| with n the cone's exact normal there, not the
// cylinder's radial one.
TEST(ReferenceShaped, FlatShadingFollowsTheConesTiltedNormal) {
  const PinholeCamera cam = Camera();
  const double r = 0.05, d = 2.0, x0 = -0.2, x1 = 0.2;
  ReferencePart part = Part(Eigen::Vector3d(x0, 0, d), Eigen::Vector3d(x1, 0, d), r, Cone(1, 5));
  part.color = Eigen::Vector3f(1.0f, 1.0f, 1.0f);
  const ReferenceRender out = Render(part);
  const double slope = r * (5 - 1) / (x1 - x0);
  int checked = 0;
  for (int v = 57; v <= 64; ++v)
    for (int u = 70; u <= 95; ++u) {
      ASSERT_EQ(out.mask.at(u, v), 255) << u << ", " << v;
      const Eigen::Vector3d ray((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0);
      const Eigen::Vector3d p = out.depth.at(u, v) * ray;
      const Eigen::Vector3d radial = Eigen::Vector3d(0, p.y(), p.z() - d).normalized();
      const Eigen::Vector3d n = (radial - slope * Eigen::Vector3d::UnitX()).normalized();
      const Eigen::Vector3d e = -p.normalized();
      const double expected = 255 * (0.35 + 0.65 * std::abs(n.dot(e)));
      const double cylinder = 255 * (0.35 + 0.65 * std::abs(radial.dot(e)));
      EXPECT_GT(cylinder - expected, 8);  // the tilt is visible
      EXPECT_NEAR(out.color.at(u, v, 0), expected, 3.0) << u << ", " << v;
      ++checked;
    }
  EXPECT_EQ(checked, 8 * 26);
}

// A plain shape draws exactly what the thesis's cylinder draws, whatever the width direction.
TEST(ReferenceShaped, PlainShapeIsTheCylinder) {
  const Eigen::Vector3d a(-0.3, 0.05, 2.0), b(0.3, -0.05, 2.2);
  const ReferenceRender plain = Render(Part(a, b, 0.1, PartShape{}));
  const ReferenceRender also = Render(Part(a, b, 0.1, Uniform(1, 1)));
  EXPECT_EQ(plain.mask.data, also.mask.data);
  EXPECT_EQ(plain.color.data, also.color.data);
  EXPECT_EQ(plain.depth.data, also.depth.data);
}

TEST(ReferenceShaped, RejectsBadShapesAndWidthDirections) {
  const Eigen::Vector3d a(0, 0, 1), b(0, 0, 1.5);
  for (double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
    PartShape shape;
    shape.depth[3] = bad;
    EXPECT_THROW(Render(Part(a, b, 0.1, shape)), CheckError) << bad;
  }
  EXPECT_THROW(Render(Part(a, b, 0.1, Uniform(1.2, 0.8),
                           Eigen::Vector3d(std::numeric_limits<double>::quiet_NaN(), 0, 0))),
               CheckError);
}

}  // namespace
}  // namespace reenact
