#include "common/render/reference_renderer.h"

#include <algorithm>
#include <array>
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

void CheckCrop(const ReferenceCrop& crop, const std::string& name) {
  REENACT_CHECK(!crop.color.empty() && crop.color.channels == 3,
                name + "crop colour must be non-empty RGB");
  REENACT_CHECK(crop.mask.channels == 1 && crop.mask.width == crop.color.width &&
                    crop.mask.height == crop.color.height,
                name + "crop mask must be single-channel and the colour's size");
  crop.camera.Check();
  REENACT_CHECK(crop.camera.width == crop.color.width && crop.camera.height == crop.color.height,
                name + "crop camera must have the crop's size");
  const auto empty_or_crop_sized = [&crop](const auto& image) {
    return image.empty() || (image.channels == 1 && image.width == crop.color.width &&
                             image.height == crop.color.height);
  };
  REENACT_CHECK(empty_or_crop_sized(crop.part_labels),
                name + "crop part labels must be empty or single-channel of the crop's size");
  REENACT_CHECK(empty_or_crop_sized(crop.depth_m),
                name + "crop depth must be empty or single-channel of the crop's size");
  REENACT_CHECK(crop.normals.empty() ||
                    (crop.normals.channels == 3 && crop.normals.width == crop.color.width &&
                     crop.normals.height == crop.color.height),
                name + "crop normals must be empty or 3-channel of the crop's size");
  REENACT_CHECK(std::all_of(crop.normals.data.begin(), crop.normals.data.end(),
                            [](float v) { return std::isfinite(v); }),
                name + "crop normals must be finite");
}

void CheckPart(const ReferencePart& part, size_t index) {
  const std::string name = "reference part " + std::to_string(index) + ": ";
  const Cylinder& c = part.cylinder;
  REENACT_CHECK(c.a.allFinite() && c.b.allFinite() && std::isfinite(c.radius) && c.radius > 0,
                name + "axis end points must be finite and the radius positive");
  REENACT_CHECK(c.shape.IsValid(), name + "shape values must be finite and > 0 (PartShape::IsValid)");
  REENACT_CHECK(!c.width_direction || c.width_direction->allFinite(),
                name + "width direction must be finite");
  REENACT_CHECK(part.color.allFinite(), name + "colour must be finite");
  REENACT_CHECK(part.candidates.size() <= static_cast<size_t>(kMaxTextureCandidates),
                name + "at most " + std::to_string(kMaxTextureCandidates) + " texture candidates");
  for (const ReferenceCandidate& candidate : part.candidates) {
    REENACT_CHECK(candidate.crop != nullptr && candidate.stored_frame >= 0,
                  name + "every candidate needs a crop and a stored_frame >= 0");
    REENACT_CHECK(candidate.stored_from_viewer.allFinite(),
                  name + "stored_from_viewer must be finite");
    REENACT_CHECK(std::isfinite(candidate.weight) && candidate.weight >= 0,
                  name + "candidate weights must be finite and >= 0");
    REENACT_CHECK(candidate.stored_light.allFinite(), name + "stored_light must be finite");
    REENACT_CHECK(
        candidate.fallback || &candidate == &part.candidates.front() || !(&candidate - 1)->fallback,
        name + "fallback candidates must follow every ranked one");
    CheckCrop(*candidate.crop, name);
  }
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

struct CandidateSample {
  bool usable = false;
  bool other_part = false;  // usable, and the label map gives the texel to another part
  bool visible = false;
  Eigen::Vector3d rgb = Eigen::Vector3d::Zero();  // 0-255, where usable
  double u = -1, v = -1;
};

// The rules of texturing.h for one candidate at the viewer-frame point p of unit normal n.
CandidateSample SampleCandidate(const ReferenceCandidate& candidate, const Eigen::Vector3d& p,
                                const Eigen::Vector3d& n, int part_label, bool test_visibility,
                                const ReferenceRenderOptions& options) {
  CandidateSample out;
  const ReferenceCrop& crop = *candidate.crop;
  const Eigen::Vector4d ps = candidate.stored_from_viewer * p.homogeneous();
  const Eigen::Vector3d q = ps.head<3>() / ps.w();
  if (!(q.z() > 0)) return out;
  const double u = crop.camera.fx * q.x() / q.z() + crop.camera.cx;
  const double v = crop.camera.fy * q.y() / q.z() + crop.camera.cy;
  const int w = crop.color.width, h = crop.color.height;
  if (!(u >= -0.5 && u <= w - 0.5 && v >= -0.5 && v <= h - 0.5)) return out;
  if (!SampleCrop(crop, u, v, out.rgb)) return out;
  const int x = std::clamp(static_cast<int>(std::floor(u + 0.5)), 0, w - 1);
  const int y = std::clamp(static_cast<int>(std::floor(v + 0.5)), 0, h - 1);
  if (!options.subject_light.isZero(0)) {
    Eigen::Vector3d normal = n;
    if (!crop.normals.empty()) {
      const Eigen::Vector3d stored(crop.normals.at(x, y, 0), crop.normals.at(x, y, 1),
                                   crop.normals.at(x, y, 2));
      if (!stored.isZero(0))
        normal =
            (candidate.stored_from_viewer.topLeftCorner<3, 3>().transpose() * stored).normalized();
    }
    out.rgb *=
        SubjectShade(normal, options.subject_light) / SubjectShade(normal, candidate.stored_light);
  }
  out.usable = true;
  out.u = u;
  out.v = v;
  if (!test_visibility || crop.part_labels.empty()) return out;
  if (crop.part_labels.at(x, y) != part_label) {
    out.other_part = true;
    return out;
  }
  if (!crop.depth_m.empty()) {
    const double d = crop.depth_m.at(x, y);
    if (d > 0 && !(std::abs(d - q.z()) <= options.depth_tolerance_m)) return out;
  }
  out.visible = true;
  return out;
}

struct Contributor {
  int candidate = -1;
  double weight = 0;  // normalised
};

// The colour of a fragment under the part's mode; false where no candidate colours it.
bool ShadeTextured(const ReferencePart& part, const Eigen::Vector3d& p,
                   const Eigen::Vector3d& normal, const ReferenceRenderOptions& options,
                   Eigen::Vector3d& rgb, std::array<CandidateSample, kMaxTextureCandidates>& s,
                   std::array<Contributor, kMaxTextureCandidates>& contributors, int& count) {
  count = 0;
  const bool visibility = part.texturing != TexturingMode::kFirst;
  const int ranked =
      static_cast<int>(std::count_if(part.candidates.begin(), part.candidates.end(),
                                     [](const ReferenceCandidate& c) { return !c.fallback; }));
  const int n = visibility ? ranked : 1;
  const int label = PartLabel(part.part);
  for (int i = 0; i < n; ++i)
    s[i] = SampleCandidate(part.candidates[i], p, normal, label, visibility, options);
  if (part.texturing == TexturingMode::kBlendVisible) {
    double total = 0;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int i = 0; i < n; ++i) {
      if (!s[i].visible || !(part.candidates[i].weight > 0)) continue;
      total += part.candidates[i].weight;
      sum += part.candidates[i].weight * s[i].rgb;
      contributors[count++] = {i, part.candidates[i].weight};
    }
    if (total > 0) {
      rgb = sum / total;
      for (int j = 0; j < count; ++j) contributors[j].weight /= total;
      return true;
    }
    count = 0;
  }
  int chosen = -1;
  for (int i = 0; i < n && chosen < 0; ++i)
    if (s[i].visible) chosen = i;
  for (int i = 0; i < n && chosen < 0; ++i)
    if (s[i].usable) chosen = i;
  if (chosen < 0) return false;
  if (visibility && s[chosen].other_part) {
    const int total = static_cast<int>(part.candidates.size());
    for (int i = ranked; i < total; ++i) {
      s[i] = SampleCandidate(part.candidates[i], p, normal, label, true, options);
      if (s[i].visible) {
        chosen = i;
        break;
      }
    }
  }
  rgb = s[chosen].rgb;
  contributors[0] = {chosen, 1.0};
  count = 1;
  return true;
}

}  // namespace

void ReferenceRenderOptions::Check() const {
  REENACT_CHECK(segments >= 3, "segments must be >= 3");
  REENACT_CHECK(std::isfinite(near_z) && near_z > 0, "near_z must be positive and finite");
  REENACT_CHECK(!std::isnan(far_z) && far_z > near_z, "far_z must exceed near_z");
  REENACT_CHECK(clear_color.minCoeff() >= 0 && clear_color.maxCoeff() <= 255,
                "clear_color must lie in [0, 255]");
  REENACT_CHECK(std::isfinite(depth_tolerance_m) && depth_tolerance_m >= 0,
                "depth_tolerance_m must be finite and >= 0");
  REENACT_CHECK(subject_light.allFinite(), "subject_light must be finite");
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
  out.source_frame = Image<int32_t>(w, h, kMaxTextureCandidates, -1);
  out.source_pixel = Image<float>(w, h, 2 * kMaxTextureCandidates, -1.0f);
  out.source_weight = Image<float>(w, h, kMaxTextureCandidates, 0.0f);

  const CylinderMesh mesh = MakeUnitCylinderMesh(options.segments);
  std::vector<Eigen::Vector3i> triangles;
  for (size_t t = 0; t < mesh.indices.size(); t += 3)
    triangles.emplace_back(mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]);
  std::vector<RasterVertex> vertices(mesh.positions.size());

  for (size_t index = 0; index < parts.size(); ++index) {
    const ReferencePart& part = parts[index];
    const Cylinder& c = part.cylinder;
    if ((c.b - c.a).norm() < 1e-12) continue;
    const Eigen::Matrix4d viewer_from_cylinder = ViewerFromUnitCylinder(c);
    const Eigen::Matrix3d linear = viewer_from_cylinder.topLeftCorner<3, 3>();
    const Eigen::Matrix3d normal_linear = NormalFromUnitCylinder(viewer_from_cylinder);
    const Eigen::Vector3d offset = viewer_from_cylinder.topRightCorner<3, 1>();
    for (size_t v = 0; v < vertices.size(); ++v) {
      const Eigen::Vector3d unit = mesh.positions[v].cast<double>();
      const Eigen::Vector3d unit_normal = mesh.normals[v].cast<double>();
      vertices[v].position = linear * ShapedUnitPosition(c.shape, unit, unit_normal) + offset;
      const Eigen::Vector3d normal = normal_linear * ShapedUnitNormal(c.shape, unit, unit_normal);
      for (int k = 0; k < 3; ++k) vertices[v].attributes[k] = static_cast<float>(normal[k]);
    }
    const auto id = static_cast<int32_t>(index);
    rasterizer.DrawMesh(vertices, triangles, {}, [&](const RasterFragment& f) {
      const double z = f.depth;
      const Eigen::Vector3d p((f.x - camera.cx) / camera.fx * z, (f.y - camera.cy) / camera.fy * z,
                              z);
      Eigen::Vector3d rgb;
      std::array<CandidateSample, kMaxTextureCandidates> samples;
      std::array<Contributor, kMaxTextureCandidates> contributors;
      int count = 0;
      const Eigen::Vector3d n =
          Eigen::Vector3d(f.attributes[0], f.attributes[1], f.attributes[2]).normalized();
      if (!part.candidates.empty()) {
        if (!ShadeTextured(part, p, n, options, rgb, samples, contributors, count)) return false;
      } else {
        const double lambert = std::abs(n.dot(-p.normalized()));
        rgb = 255.0 * (0.35 + 0.65 * lambert) * part.color.cast<double>();
      }
      for (int k = 0; k < 3; ++k) out.color.at(f.x, f.y, k) = ToByte(rgb[k]);
      out.mask.at(f.x, f.y) = 255;
      out.part.at(f.x, f.y) = id;
      for (int j = 0; j < kMaxTextureCandidates; ++j) {
        const bool used = j < count;
        const int i = used ? contributors[j].candidate : -1;
        out.source_frame.at(f.x, f.y, j) = used ? part.candidates[i].stored_frame : -1;
        out.source_pixel.at(f.x, f.y, 2 * j) = used ? static_cast<float>(samples[i].u) : -1.0f;
        out.source_pixel.at(f.x, f.y, 2 * j + 1) = used ? static_cast<float>(samples[i].v) : -1.0f;
        out.source_weight.at(f.x, f.y, j) = used ? static_cast<float>(contributors[j].weight) : 0;
      }
      return true;
    });
  }
  out.depth = rasterizer.depth();
  return out;
}

}  // namespace reenact
