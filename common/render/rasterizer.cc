#include "common/render/rasterizer.h"

#include <algorithm>
#include <cmath>

#include "common/error/check.h"

namespace reenact {
namespace {

constexpr int kSubpixelBits = 8;
constexpr double kSubpixelScale = 1 << kSubpixelBits;
constexpr int kMaxPolygon = 3 + 6;  // each clipping plane adds at most one vertex

// A clipping plane dot(normal, p) + offset >= 0 in the camera frame.
struct Plane {
  Eigen::Vector3d normal;
  double offset;
  double Distance(const Eigen::Vector3d& p) const { return normal.dot(p) + offset; }
};

bool Before(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  if (a.x() != b.x()) return a.x() < b.x();
  if (a.y() != b.y()) return a.y() < b.y();
  return a.z() < b.z();
}

// The point where segment (a, b) crosses the plane, computed in an order that does not
// depend on the segment's direction so that neighbouring triangles agree on it.
RasterVertex Intersect(const RasterVertex& a, double da, const RasterVertex& b, double db,
                       int attribute_count) {
  if (Before(b.position, a.position)) return Intersect(b, db, a, da, attribute_count);
  const double t = da / (da - db);
  RasterVertex v;
  v.position = a.position + t * (b.position - a.position);
  for (int k = 0; k < attribute_count; ++k)
    v.attributes[k] = static_cast<float>(a.attributes[k] + t * (b.attributes[k] - a.attributes[k]));
  return v;
}

int ClipPolygon(const Plane& plane, const RasterVertex* in, int n, RasterVertex* out,
                int attribute_count) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const RasterVertex& a = in[i];
    const RasterVertex& b = in[(i + 1) % n];
    const double da = plane.Distance(a.position);
    const double db = plane.Distance(b.position);
    if (da >= 0) out[m++] = a;
    if ((da >= 0) != (db >= 0)) out[m++] = Intersect(a, da, b, db, attribute_count);
  }
  return m;
}

struct ScreenVertex {
  int64_t x, y;  // fixed point, 1/256 pixel
  double inv_z;
};

bool IsTopLeft(const ScreenVertex& from, const ScreenVertex& to) {
  const int64_t dx = to.x - from.x, dy = to.y - from.y;
  return (dy == 0 && dx > 0) || dy < 0;
}

// A vertex on screen: its projection in fixed point, and 1 / z.
ScreenVertex ToScreen(const PinholeCamera& camera, const Eigen::Vector3d& p) {
  const double u = camera.fx * p.x() / p.z() + camera.cx;
  const double w = camera.fy * p.y() / p.z() + camera.cy;
  return {std::llround(u * kSubpixelScale), std::llround(w * kSubpixelScale), 1.0 / p.z()};
}

// The edge function of p -> q at fixed-point (x, y): twice the signed area of (p, q, (x, y)).
int64_t Edge(const ScreenVertex& p, const ScreenVertex& q, int64_t x, int64_t y) {
  return (q.x - p.x) * (y - p.y) - (q.y - p.y) * (x - p.x);
}

// The pixels whose centres lie in a triangle's bounding box, within the image; empty when
// x0 > x1 or y0 > y1.
struct PixelBox {
  int x0, x1, y0, y1;
};

PixelBox CoveredPixels(const ScreenVertex (&s)[3], int width, int height) {
  const int64_t min_x = std::min({s[0].x, s[1].x, s[2].x});
  const int64_t max_x = std::max({s[0].x, s[1].x, s[2].x});
  const int64_t min_y = std::min({s[0].y, s[1].y, s[2].y});
  const int64_t max_y = std::max({s[0].y, s[1].y, s[2].y});
  auto ceil_px = [](int64_t f) { return (f + (1 << kSubpixelBits) - 1) >> kSubpixelBits; };
  PixelBox box;
  box.x0 = static_cast<int>(std::max<int64_t>(0, ceil_px(min_x)));
  box.x1 = static_cast<int>(std::min<int64_t>(width - 1, max_x >> kSubpixelBits));
  box.y0 = static_cast<int>(std::max<int64_t>(0, ceil_px(min_y)));
  box.y1 = static_cast<int>(std::min<int64_t>(height - 1, max_y >> kSubpixelBits));
  return box;
}

// A counter-clockwise triangle's edge functions at pixel (x0, y0), their steps per pixel in
// x and y, and the top-left rule's bias. Edge k is opposite vertex k: edge 0 = (1 -> 2),
// 1 = (2 -> 0), 2 = (0 -> 1).
struct EdgeFunctions {
  int64_t row[3], step_x[3], step_y[3], bias[3];
};

EdgeFunctions SetUpEdges(const ScreenVertex (&s)[3], int x0, int y0) {
  const int from[3] = {1, 2, 0}, to[3] = {2, 0, 1};
  EdgeFunctions edges;
  const int64_t px0 = static_cast<int64_t>(x0) << kSubpixelBits;
  const int64_t py0 = static_cast<int64_t>(y0) << kSubpixelBits;
  for (int k = 0; k < 3; ++k) {
    const ScreenVertex& p = s[from[k]];
    const ScreenVertex& q = s[to[k]];
    edges.row[k] = Edge(p, q, px0, py0);
    edges.step_x[k] = -(q.y - p.y) << kSubpixelBits;
    edges.step_y[k] = (q.x - p.x) << kSubpixelBits;
    edges.bias[k] = IsTopLeft(p, q) ? 0 : -1;
  }
  return edges;
}

}  // namespace

void RasterOptions::Check() const {
  REENACT_CHECK(std::isfinite(near_z) && near_z > 0, "near_z must be positive and finite");
  REENACT_CHECK(!std::isnan(far_z) && far_z > near_z, "far_z must exceed near_z");
  REENACT_CHECK(attribute_count >= 0 && attribute_count <= kMaxRasterAttributes,
                "attribute_count must lie in [0, 8]");
}

Rasterizer::Rasterizer(const PinholeCamera& camera, const RasterOptions& options)
    : camera_(camera), options_(options) {
  camera.Check();
  options.Check();
  REENACT_CHECK(camera.distortion.IsZero(), "the rasterizer needs an undistorted camera");
  depth_ = Image<double>(camera.width, camera.height, 1, std::numeric_limits<double>::infinity());
}

void Rasterizer::Clear() {
  std::fill(depth_.data.begin(), depth_.data.end(), std::numeric_limits<double>::infinity());
}

void Rasterizer::DrawMesh(std::span<const RasterVertex> vertices,
                          std::span<const Eigen::Vector3i> triangles,
                          std::span<const int> primitive_ids, FragmentShader shader) {
  REENACT_CHECK(primitive_ids.empty() || primitive_ids.size() == triangles.size(),
                "primitive_ids must be empty or one per triangle");
  const int n = static_cast<int>(vertices.size());
  for (size_t t = 0; t < triangles.size(); ++t) {
    const Eigen::Vector3i& tri = triangles[t];
    REENACT_CHECK(tri.minCoeff() >= 0 && tri.maxCoeff() < n, "triangle index out of range");
    DrawTriangle(vertices[tri[0]], vertices[tri[1]], vertices[tri[2]],
                 primitive_ids.empty() ? static_cast<int>(t) : primitive_ids[t], shader);
  }
}

void Rasterizer::DrawTriangle(const RasterVertex& a, const RasterVertex& b, const RasterVertex& c,
                              int primitive_id, FragmentShader shader) {
  REENACT_CHECK(a.position.allFinite() && b.position.allFinite() && c.position.allFinite(),
                "triangle vertices must be finite");
  ++stats_.triangles_submitted;
  const Eigen::Vector3d normal = (b.position - a.position).cross(c.position - a.position);
  const double facing = normal.dot(a.position);
  if (facing == 0) return;  // degenerate, or seen exactly edge-on
  const bool front = facing < 0;
  if ((options_.cull == CullMode::kBack && !front) || (options_.cull == CullMode::kFront && front))
    return;

  const double guard_x = camera_.width, guard_y = camera_.height;
  const double fx = camera_.fx, fy = camera_.fy, cx = camera_.cx, cy = camera_.cy;
  std::array<Plane, 6> planes = {{
      {Eigen::Vector3d(0, 0, 1), -options_.near_z},
      {Eigen::Vector3d(fx, 0, cx + guard_x), 0},                        // u >= -guard
      {Eigen::Vector3d(-fx, 0, camera_.width - 1 + guard_x - cx), 0},   // u <= W-1+guard
      {Eigen::Vector3d(0, fy, cy + guard_y), 0},                        // v >= -guard
      {Eigen::Vector3d(0, -fy, camera_.height - 1 + guard_y - cy), 0},  // v <= H-1+guard
      {Eigen::Vector3d(0, 0, -1), options_.far_z},
  }};
  const int plane_count = std::isfinite(options_.far_z) ? 6 : 5;

  std::array<RasterVertex, kMaxPolygon> poly_a, poly_b;
  poly_a[0] = a;
  poly_a[1] = b;
  poly_a[2] = c;
  int n = 3;
  bool all_inside = true;
  for (int p = 0; p < plane_count && all_inside; ++p)
    for (const RasterVertex* v : {&a, &b, &c})
      if (planes[p].Distance(v->position) < 0) all_inside = false;
  if (all_inside) {
    RasterizeClipped(a, b, c, primitive_id, front, shader);
    return;
  }
  RasterVertex* in = poly_a.data();
  RasterVertex* out = poly_b.data();
  for (int p = 0; p < plane_count && n >= 3; ++p) {
    n = ClipPolygon(planes[p], in, n, out, options_.attribute_count);
    std::swap(in, out);
  }
  for (int i = 1; i + 1 < n; ++i)
    RasterizeClipped(in[0], in[i], in[i + 1], primitive_id, front, shader);
}

void Rasterizer::RasterizeClipped(const RasterVertex& a, const RasterVertex& b,
                                  const RasterVertex& c, int primitive_id, bool front_facing,
                                  FragmentShader shader) {
  const RasterVertex* v[3] = {&a, &b, &c};
  ScreenVertex s[3];
  for (int i = 0; i < 3; ++i) s[i] = ToScreen(camera_, v[i]->position);
  int64_t area = Edge(s[0], s[1], s[2].x, s[2].y);
  if (area == 0) return;
  if (area < 0) {
    std::swap(s[1], s[2]);
    std::swap(v[1], v[2]);
    area = -area;
  }
  ++stats_.triangles_rasterized;

  const PixelBox box = CoveredPixels(s, camera_.width, camera_.height);
  const int x0 = box.x0, x1 = box.x1, y0 = box.y0, y1 = box.y1;
  if (x0 > x1 || y0 > y1) return;
  EdgeFunctions edges = SetUpEdges(s, x0, y0);
  int64_t* row = edges.row;
  const int64_t *step_x = edges.step_x, *step_y = edges.step_y, *bias = edges.bias;

  const int attribute_count = options_.attribute_count;
  const double inv_area = 1.0 / static_cast<double>(area);
  // Attributes pre-divided by z, so that interpolation is linear in screen space.
  double attr_over_z[3][kMaxRasterAttributes];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < attribute_count; ++k) attr_over_z[i][k] = v[i]->attributes[k] * s[i].inv_z;

  RasterFragment fragment;
  fragment.primitive_id = primitive_id;
  fragment.front_facing = front_facing;
  for (int y = y0; y <= y1; ++y) {
    int64_t e[3] = {row[0], row[1], row[2]};
    double* depth_row = &depth_.at(0, y);
    for (int x = x0; x <= x1; ++x) {
      if (e[0] + bias[0] >= 0 && e[1] + bias[1] >= 0 && e[2] + bias[2] >= 0) {
        const double l0 = e[0] * inv_area, l1 = e[1] * inv_area, l2 = e[2] * inv_area;
        const double inv_z = l0 * s[0].inv_z + l1 * s[1].inv_z + l2 * s[2].inv_z;
        const double z = 1.0 / inv_z;
        if (!options_.depth_test || z < depth_row[x]) {
          fragment.x = x;
          fragment.y = y;
          fragment.depth = z;
          for (int k = 0; k < attribute_count; ++k)
            fragment.attributes[k] = static_cast<float>(
                z * (l0 * attr_over_z[0][k] + l1 * attr_over_z[1][k] + l2 * attr_over_z[2][k]));
          ++stats_.fragments_shaded;
          if (shader(fragment) && options_.depth_write) depth_row[x] = z;
        }
      }
      for (int k = 0; k < 3; ++k) e[k] += step_x[k];
    }
    for (int k = 0; k < 3; ++k) row[k] += step_y[k];
  }
}

}  // namespace reenact
