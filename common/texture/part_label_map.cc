#include "common/texture/part_label_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/error/check.h"
#include "common/render/cylinder_mesh.h"
#include "common/render/rasterizer.h"

namespace reenact {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Smallest t > 0 at which the ray t d (from the origin) meets the closed cylinder; +inf if
// none.
double RayCylinderHit(const Eigen::Vector3d& d, const Cylinder& c) {
  const Eigen::Vector3d axis = c.b - c.a;
  const double length = axis.norm();
  if (!(length > 0)) return kInf;
  const Eigen::Vector3d n = axis / length;
  const double r2 = c.radius * c.radius;
  double best = kInf;
  // Side: |(t d - a)_perp|^2 = r^2 with 0 <= (t d - a) . n <= length.
  const Eigen::Vector3d d_perp = d - d.dot(n) * n;
  const Eigen::Vector3d a_perp = c.a - c.a.dot(n) * n;
  const double qa = d_perp.squaredNorm(), qb = -2 * d_perp.dot(a_perp),
               qc = a_perp.squaredNorm() - r2;
  if (qa > 1e-18) {
    const double disc = qb * qb - 4 * qa * qc;
    if (disc >= 0) {
      const double root = std::sqrt(disc);
      for (double t : {(-qb - root) / (2 * qa), (-qb + root) / (2 * qa)}) {
        if (!(t > 0) || t >= best) continue;
        const double s = (t * d - c.a).dot(n);
        if (s >= 0 && s <= length) best = t;
      }
    }
  }
  // Caps: planes through a and b with normal n.
  const double dn = d.dot(n);
  if (std::abs(dn) > 1e-18)
    for (const Eigen::Vector3d* centre : {&c.a, &c.b}) {
      const double t = centre->dot(n) / dn;
      if (t > 0 && t < best && (t * d - *centre).squaredNorm() <= r2) best = t;
    }
  return best;
}

// A cylinder's axis projected into the image, clipped to z >= kLabelMapNearZ.
struct ProjectedAxis {
  Eigen::Vector2d p0, p1;     // pixels
  double rho0 = 0, rho1 = 0;  // projected radius at each end, pixels
  // Shaped parts: the clipped ends' axis parameters t (0 at a, 1 at b) and depths, and the
  // largest distance of each ring from the axis in radii (PartShape::RingReach).
  bool shaped = false;
  double t0 = 0, t1 = 1, z0 = 1, z1 = 1;
  std::array<double, kShapeRings> ring_scale{};
};

std::optional<ProjectedAxis> ProjectAxis(const Cylinder& c, const PinholeCamera& camera) {
  Eigen::Vector3d a = c.a, b = c.b;
  double t0 = 0, t1 = 1;
  if (a.z() < kLabelMapNearZ && b.z() < kLabelMapNearZ) return std::nullopt;
  if (a.z() < kLabelMapNearZ || b.z() < kLabelMapNearZ) {
    const double s = (kLabelMapNearZ - a.z()) / (b.z() - a.z());
    const Eigen::Vector3d cut = a + s * (b - a);
    (a.z() < kLabelMapNearZ ? t0 : t1) = s;
    (a.z() < kLabelMapNearZ ? a : b) = cut;
  }
  const auto project = [&camera](const Eigen::Vector3d& p) {
    return Eigen::Vector2d(camera.fx * p.x() / p.z() + camera.cx,
                           camera.fy * p.y() / p.z() + camera.cy);
  };
  ProjectedAxis axis{project(a), project(b), camera.fx * c.radius / a.z(),
                     camera.fx * c.radius / b.z()};
  if (!c.shape.IsCylinder()) {
    axis.shaped = true;
    axis.t0 = t0;
    axis.t1 = t1;
    axis.z0 = a.z();
    axis.z1 = b.z();
    for (int k = 0; k < kShapeRings; ++k) axis.ring_scale[k] = c.shape.RingReach(k);
  }
  return axis;
}

// The shaped axis's ring scale at image parameter s in [0, 1] of the projected axis: the 3D
// point that projects there is at lambda = s z0 / ((1 - s) z1 + s z0) of the clipped axis.
double RingScaleAt(const ProjectedAxis& axis, double s) {
  const double lambda = s * axis.z0 / ((1 - s) * axis.z1 + s * axis.z0);
  return RingValueAt(axis.ring_scale, axis.t0 + lambda * (axis.t1 - axis.t0));
}

// Pixel box (inclusive) that holds the cylinder's image: the projection of its axis-aligned
// 3D bounding box, grown by a pixel; the whole image where that box reaches z < near.
struct PixelBox {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  bool Contains(int x, int y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
  bool Empty() const { return x0 > x1 || y0 > y1; }
};

// Largest distance of the part's surface from its axis, metres.
double Reach(const Cylinder& c) {
  double scale = 0;
  for (int k = 0; k < kShapeRings; ++k) scale = std::max(scale, c.shape.RingReach(k));
  return c.radius * scale;
}

PixelBox ImageBox(const Cylinder& c, const PinholeCamera& camera) {
  const double reach = Reach(c);
  const Eigen::Vector3d lo = c.a.cwiseMin(c.b).array() - reach;
  const Eigen::Vector3d hi = c.a.cwiseMax(c.b).array() + reach;
  if (hi.z() <= 0) return {};  // wholly behind: never hit
  if (lo.z() < kLabelMapNearZ) return {0, 0, camera.width - 1, camera.height - 1};
  double u0 = kInf, v0 = kInf, u1 = -kInf, v1 = -kInf;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d p(corner & 1 ? hi.x() : lo.x(), corner & 2 ? hi.y() : lo.y(),
                            corner & 4 ? hi.z() : lo.z());
    const double u = camera.fx * p.x() / p.z() + camera.cx;
    const double v = camera.fy * p.y() / p.z() + camera.cy;
    u0 = std::min(u0, u);
    u1 = std::max(u1, u);
    v0 = std::min(v0, v);
    v1 = std::max(v1, v);
  }
  const auto clamp_to = [](double value, int size) {
    return static_cast<int>(std::clamp(value, -1.0, static_cast<double>(size)));
  };
  return {clamp_to(std::floor(u0) - 1, camera.width), clamp_to(std::floor(v0) - 1, camera.height),
          clamp_to(std::ceil(u1) + 1, camera.width), clamp_to(std::ceil(v1) + 1, camera.height)};
}

double CapsuleDistance(const ProjectedAxis& axis, const Eigen::Vector2d& pixel) {
  const Eigen::Vector2d e = axis.p1 - axis.p0;
  const double e2 = e.squaredNorm();
  const double s = e2 > 0 ? std::clamp((pixel - axis.p0).dot(e) / e2, 0.0, 1.0) : 0.0;
  const double rho = (1 - s) * axis.rho0 + s * axis.rho1;
  return (pixel - (axis.p0 + s * e)).norm() - (axis.shaped ? rho * RingScaleAt(axis, s) : rho);
}

// The shaped (not IsCylinder) parts' tessellated meshes rasterised over the union of their
// pixel boxes: the nearest part index per pixel (-1 where none) and its depth, ties to the
// lower part index (drawn in part order, the depth test strictly closer).
struct ShapedLayer {
  PixelBox box;                          // within the image
  std::optional<Rasterizer> rasterizer;  // over the box's crop of the camera
  Image<int8_t> part;                    // the box's size

  // Part index at image pixel (x, y), -1 where no shaped part lies; its depth where >= 0.
  int Part(int x, int y) const { return box.Contains(x, y) ? part.at(x - box.x0, y - box.y0) : -1; }
  double Depth(int x, int y) const { return rasterizer->depth().at(x - box.x0, y - box.y0); }
};

std::optional<ShapedLayer> RasterizeShapedParts(
    const std::array<std::optional<Cylinder>, kBodyPartCount>& cylinders,
    const PinholeCamera& camera) {
  ShapedLayer layer;
  layer.box = {camera.width, camera.height, -1, -1};
  for (const auto& c : cylinders) {
    if (!c || c->shape.IsCylinder() || !(c->Length() > 0)) continue;
    const PixelBox b = ImageBox(*c, camera);
    if (b.Empty()) continue;
    layer.box = {std::min(layer.box.x0, b.x0), std::min(layer.box.y0, b.y0),
                 std::max(layer.box.x1, b.x1), std::max(layer.box.y1, b.y1)};
  }
  layer.box = {std::max(layer.box.x0, 0), std::max(layer.box.y0, 0),
               std::min(layer.box.x1, camera.width - 1), std::min(layer.box.y1, camera.height - 1)};
  if (layer.box.Empty()) return std::nullopt;
  const int w = layer.box.x1 - layer.box.x0 + 1, h = layer.box.y1 - layer.box.y0 + 1;
  PinholeCamera window = camera.Cropped(layer.box.x0, layer.box.y0, w, h);
  window.distortion = Distortion{};
  RasterOptions options;
  options.near_z = kLabelMapNearZ;
  options.attribute_count = 0;
  layer.rasterizer.emplace(window, options);
  layer.part = Image<int8_t>(w, h, 1, -1);
  const CylinderMesh mesh = MakeUnitCylinderMesh(kDefaultCylinderSegments);
  std::vector<Eigen::Vector3i> triangles;
  for (size_t t = 0; t < mesh.indices.size(); t += 3)
    triangles.emplace_back(mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]);
  std::vector<RasterVertex> vertices(mesh.positions.size());
  for (int p = 0; p < kBodyPartCount; ++p) {
    const auto& c = cylinders[p];
    if (!c || c->shape.IsCylinder() || !(c->Length() > 0)) continue;
    const Eigen::Matrix4d viewer_from_cylinder = ViewerFromUnitCylinder(*c);
    for (size_t v = 0; v < vertices.size(); ++v)
      vertices[v].position = viewer_from_cylinder.topLeftCorner<3, 3>() *
                                 ShapedUnitPosition(c->shape, mesh.positions[v].cast<double>(),
                                                    mesh.normals[v].cast<double>()) +
                             viewer_from_cylinder.topRightCorner<3, 1>();
    layer.rasterizer->DrawMesh(vertices, triangles, {}, [&](const RasterFragment& f) {
      layer.part.at(f.x, f.y) = static_cast<int8_t>(p);
      return true;
    });
  }
  return layer;
}

}  // namespace

ImageLabel8 RenderPartLabelMap(const std::array<std::optional<Cylinder>, kBodyPartCount>& cylinders,
                               const PinholeCamera& camera, const ImageGray8& mask) {
  camera.Check();
  REENACT_CHECK(mask.channels == 1 && mask.width == camera.width && mask.height == camera.height,
                "part label map: the mask must be single-channel of the camera's size");
  std::array<std::optional<ProjectedAxis>, kBodyPartCount> axes;
  std::array<PixelBox, kBodyPartCount> boxes;
  for (int p = 0; p < kBodyPartCount; ++p) {
    if (!cylinders[p]) continue;
    const Cylinder& c = *cylinders[p];
    REENACT_CHECK(c.a.allFinite() && c.b.allFinite() && std::isfinite(c.radius) && c.radius > 0,
                  "part label map: cylinders must be finite with a positive radius");
    REENACT_CHECK(c.shape.IsValid(), "part label map: shape values must be finite and > 0");
    REENACT_CHECK(!c.width_direction || c.width_direction->allFinite(),
                  "part label map: width directions must be finite");
    if (c.Length() > 0) {
      axes[p] = ProjectAxis(c, camera);
      if (c.shape.IsCylinder()) boxes[p] = ImageBox(c, camera);
    }
  }
  const std::optional<ShapedLayer> shaped = RasterizeShapedParts(cylinders, camera);
  ImageLabel8 labels(camera.width, camera.height, 1, kBackgroundLabel);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      if (mask.at(x, y) < 128) continue;
      const Eigen::Vector3d d((x - camera.cx) / camera.fx, (y - camera.cy) / camera.fy, 1.0);
      int best = -1;
      double best_t = kInf;
      for (int p = 0; p < kBodyPartCount; ++p) {
        if (!boxes[p].Contains(x, y)) continue;
        const double t = RayCylinderHit(d, *cylinders[p]);
        if (t < best_t) {
          best_t = t;
          best = p;
        }
      }
      if (shaped) {
        const int p = shaped->Part(x, y);
        const double t = p >= 0 ? shaped->Depth(x, y) : kInf;
        if (p >= 0 && (t < best_t || (t == best_t && p < best))) {
          best_t = t;
          best = p;
        }
      }
      if (best < 0) {
        double best_distance = kInf;
        for (int p = 0; p < kBodyPartCount; ++p) {
          if (!axes[p]) continue;
          const double distance = CapsuleDistance(*axes[p], Eigen::Vector2d(x, y));
          if (distance < best_distance) {
            best_distance = distance;
            best = p;
          }
        }
      }
      if (best >= 0) labels.at(x, y) = static_cast<uint8_t>(PartLabel(static_cast<BodyPart>(best)));
    }
  return labels;
}

ImageLabel8 PartLabelMapOfFrame(const Skeleton& skeleton_in_sensor, const RadiusRatios& ratios,
                                const PinholeCamera& crop_camera, const ImageGray8& mask,
                                const PartExtensions& extensions, const PartShapes& shapes) {
  return RenderPartLabelMap(PoseCylinders(skeleton_in_sensor, ratios, extensions, shapes),
                            crop_camera, mask);
}

}  // namespace reenact
