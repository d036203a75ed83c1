#include "common/render/reference_renderer.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/error/check.h"
#include "common/render/rasterizer.h"

namespace reenact {
namespace {

uint8_t ToByte(double value_0_255) {
  return static_cast<uint8_t>(std::lround(std::clamp(value_0_255, 0.0, 255.0)));
}

void CheckPart(const ReferencePart& part, size_t index) {
  const std::string name = "reference part " + std::to_string(index) + ": ";
  const Cylinder& c = part.cylinder;
  REENACT_CHECK(c.a.allFinite() && c.b.allFinite() && std::isfinite(c.radius) && c.radius > 0,
                name + "axis end points must be finite and the radius positive");
  REENACT_CHECK(part.stored_from_viewer.allFinite(), name + "stored_from_viewer must be finite");
  REENACT_CHECK(part.color.allFinite(), name + "colour must be finite");
  REENACT_CHECK((part.crop != nullptr) == (part.stored_frame >= 0),
                name + "stored_frame must be >= 0 exactly when a crop is given");
  if (part.crop == nullptr) return;
  const ReferenceCrop& crop = *part.crop;
  REENACT_CHECK(!crop.color.empty() && crop.color.channels == 3,
                name + "crop colour must be non-empty RGB");
  REENACT_CHECK(crop.mask.channels == 1 && crop.mask.width == crop.color.width &&
                    crop.mask.height == crop.color.height,
                name + "crop mask must be single-channel and the colour's size");
  crop.camera.Check();
  REENACT_CHECK(crop.camera.width == crop.color.width && crop.camera.height == crop.color.height,
                name + "crop camera must have the crop's size");
}

// Bilinear sample of the premultiplied crop at pixel (u, v), clamped to the edge. Returns
// false where the sampled alpha is below 0.5; else the unpremultiplied colour, 0-255.
bool SampleCrop(const ReferenceCrop& crop, double u, double v, Eigen::Vector3d& rgb) {
  const int w = crop.color.width, h = crop.color.height;
  const double fu = std::floor(u), fv = std::floor(v);
  const double tu = u - fu, tv = v - fv;
  const int x0 = static_cast<int>(fu), y0 = static_cast<int>(fv);
  double alpha = 0;
  Eigen::Vector3d premultiplied = Eigen::Vector3d::Zero();
  for (int dy = 0; dy < 2; ++dy) {
    const int y = std::clamp(y0 + dy, 0, h - 1);
    const double wy = dy ? tv : 1 - tv;
    for (int dx = 0; dx < 2; ++dx) {
      const int x = std::clamp(x0 + dx, 0, w - 1);
      const double weight = wy * (dx ? tu : 1 - tu);
      if (weight == 0 || crop.mask.at(x, y) < 128) continue;
      alpha += weight;
      for (int c = 0; c < 3; ++c) premultiplied[c] += weight * crop.color.at(x, y, c);
    }
  }
  if (alpha < 0.5) return false;
  rgb = premultiplied / alpha;
  return true;
}

}  // namespace

void ReferenceRenderOptions::Check() const {
  REENACT_CHECK(segments >= 3, "segments must be >= 3");
  REENACT_CHECK(std::isfinite(near_z) && near_z > 0, "near_z must be positive and finite");
  REENACT_CHECK(!std::isnan(far_z) && far_z > near_z, "far_z must exceed near_z");
  REENACT_CHECK(clear_color.minCoeff() >= 0 && clear_color.maxCoeff() <= 255,
                "clear_color must lie in [0, 255]");
}

ReferenceRender RenderReference(const PinholeCamera& camera, std::span<const ReferencePart> parts,
                                const ReferenceRenderOptions& options) {
  camera.Check();
  options.Check();
  for (size_t i = 0; i < parts.size(); ++i) CheckPart(parts[i], i);

  PinholeCamera undistorted = camera;
  undistorted.distortion = Distortion{};
  RasterOptions raster_options;
  raster_options.near_z = options.near_z;
  raster_options.far_z = options.far_z;
  raster_options.attribute_count = 3;  // the viewer-frame vertex normal
  Rasterizer rasterizer(undistorted, raster_options);

  const int w = camera.width, h = camera.height;
  ReferenceRender out;
  out.color = ImageRgb8(w, h, 3);
  for (size_t i = 0; i < out.color.data.size(); ++i)
    out.color.data[i] = static_cast<uint8_t>(options.clear_color[static_cast<int>(i % 3)]);
  out.mask = ImageGray8(w, h, 1, 0);
  out.part = Image<int32_t>(w, h, 1, -1);
  out.source_frame = Image<int32_t>(w, h, 1, -1);
  out.source_pixel = Image<float>(w, h, 2, -1.0f);

  const CylinderMesh mesh = MakeUnitCylinderMesh(options.segments);
  std::vector<Eigen::Vector3i> triangles;
  for (size_t t = 0; t < mesh.indices.size(); t += 3)
    triangles.emplace_back(mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]);
  std::vector<RasterVertex> vertices(mesh.positions.size());

  for (size_t index = 0; index < parts.size(); ++index) {
    const ReferencePart& part = parts[index];
    const Cylinder& c = part.cylinder;
    if ((c.b - c.a).norm() < 1e-12) continue;
    const Eigen::Matrix4d viewer_from_cylinder = ViewerFromUnitCylinder(c.a, c.b, c.radius);
    const Eigen::Matrix3d linear = viewer_from_cylinder.topLeftCorner<3, 3>();
    const Eigen::Vector3d offset = viewer_from_cylinder.topRightCorner<3, 1>();
    for (size_t v = 0; v < vertices.size(); ++v) {
      vertices[v].position = linear * mesh.positions[v].cast<double>() + offset;
      const Eigen::Vector3d normal = linear * mesh.normals[v].cast<double>();
      for (int k = 0; k < 3; ++k) vertices[v].attributes[k] = static_cast<float>(normal[k]);
    }
    const auto id = static_cast<int32_t>(index);
    rasterizer.DrawMesh(vertices, triangles, {}, [&](const RasterFragment& f) {
      const double z = f.depth;
      const Eigen::Vector3d p((f.x - camera.cx) / camera.fx * z, (f.y - camera.cy) / camera.fy * z,
                              z);
      Eigen::Vector3d rgb;
      float su = -1.0f, sv = -1.0f;
      if (part.crop != nullptr) {
        const ReferenceCrop& crop = *part.crop;
        const Eigen::Vector4d ps = part.stored_from_viewer * p.homogeneous();
        const Eigen::Vector3d q = ps.head<3>() / ps.w();
        if (!(q.z() > 0)) return false;
        const double u = crop.camera.fx * q.x() / q.z() + crop.camera.cx;
        const double v = crop.camera.fy * q.y() / q.z() + crop.camera.cy;
        if (!(u >= -0.5 && u <= crop.color.width - 0.5 && v >= -0.5 &&
              v <= crop.color.height - 0.5))
          return false;
        if (!SampleCrop(crop, u, v, rgb)) return false;
        su = static_cast<float>(u);
        sv = static_cast<float>(v);
      } else {
        const Eigen::Vector3d n =
            Eigen::Vector3d(f.attributes[0], f.attributes[1], f.attributes[2]).normalized();
        const double lambert = std::abs(n.dot(-p.normalized()));
        rgb = 255.0 * (0.35 + 0.65 * lambert) * part.color.cast<double>();
      }
      for (int k = 0; k < 3; ++k) out.color.at(f.x, f.y, k) = ToByte(rgb[k]);
      out.mask.at(f.x, f.y) = 255;
      out.part.at(f.x, f.y) = id;
      out.source_frame.at(f.x, f.y) = part.crop != nullptr ? part.stored_frame : -1;
      out.source_pixel.at(f.x, f.y, 0) = su;
      out.source_pixel.at(f.x, f.y, 1) = sv;
      return true;
    });
  }
  out.depth = rasterizer.depth();
  return out;
}

}  // namespace reenact
