#include "common/model/cylinder_model.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/error/check.h"

namespace reenact {

RadiusRatios DefaultRadiusRatios() {
  RadiusRatios r{};
  r[Index(BodyPart::kHead)] = 0.45;
  r[Index(BodyPart::kUpperTorso)] = 0.55;
  r[Index(BodyPart::kLowerTorso)] = 0.65;
  r[Index(BodyPart::kLeftUpperArm)] = r[Index(BodyPart::kRightUpperArm)] = 0.16;
  r[Index(BodyPart::kLeftForearm)] = r[Index(BodyPart::kRightForearm)] = 0.13;
  r[Index(BodyPart::kLeftThigh)] = r[Index(BodyPart::kRightThigh)] = 0.17;
  r[Index(BodyPart::kLeftShin)] = r[Index(BodyPart::kRightShin)] = 0.12;
  return r;
}

Joint EndJoint(BodyPart part) {
  return part == BodyPart::kHead ? Joint::kHead : PartJoints(part).second;
}

double PartSurface::FactorAt(int k, double phi) const {
  if (angles == 0) return 1.0;
  const double x = phi / (2 * std::numbers::pi) * angles;
  const double lo = std::floor(x);
  const double f = x - lo;
  const int j = ((static_cast<int>(lo) % angles) + angles) % angles;
  const auto& ring = radial[static_cast<size_t>(std::clamp(k, 0, kShapeRings - 1))];
  return (1 - f) * ring[static_cast<size_t>(j)] + f * ring[static_cast<size_t>((j + 1) % angles)];
}

bool PartShape::IsCylinder() const {
  for (int k = 0; k < kShapeRings; ++k)
    if (width[k] != 1.0 || depth[k] != 1.0) return false;
  return surface.IsEmpty() && cap_depth == std::array<double, 2>{0, 0};
}

bool PartShape::IsCircular() const { return width == depth && surface.IsEmpty(); }

bool PartShape::IsValid() const {
  for (int k = 0; k < kShapeRings; ++k)
    if (!(std::isfinite(width[k]) && width[k] > 0 && std::isfinite(depth[k]) && depth[k] > 0))
      return false;
  if (surface.angles != 0 && (surface.angles < 3 || surface.angles > kMaxSurfaceAngles))
    return false;
  for (int k = 0; k < kShapeRings; ++k)
    for (int j = 0; j < surface.angles; ++j)
      if (!(std::isfinite(surface.radial[k][j]) && surface.radial[k][j] > 0)) return false;
  for (double d : cap_depth)
    if (!(std::isfinite(d) && d >= 0)) return false;
  return true;
}

double PartShape::RingReach(int k) const {
  double factor = 1.0;
  for (int j = 0; j < surface.angles; ++j) factor = std::max(factor, surface.radial[k][j]);
  return factor * std::max(width[k], depth[k]);
}

double RingValueAt(const std::array<double, kShapeRings>& rings, double t) {
  const double x = std::clamp(t, 0.0, 1.0) * (kShapeRings - 1);
  const int k = std::min(kShapeRings - 2, static_cast<int>(x));
  const double f = x - k;
  return (1 - f) * rings[k] + f * rings[k + 1];
}

std::optional<Eigen::Vector3d> PartWidthDirection(const Skeleton& skeleton, BodyPart part) {
  Joint left, right;
  if (part == BodyPart::kUpperTorso) {
    left = Joint::kLeftShoulder;
    right = Joint::kRightShoulder;
  } else if (part == BodyPart::kLowerTorso) {
    left = Joint::kLeftHip;
    right = Joint::kRightHip;
  } else {
    return std::nullopt;
  }
  const auto [ja, jb] = PartJoints(part);
  if (!skeleton.Has(ja) || !skeleton.Has(jb) || !skeleton.Has(left) || !skeleton.Has(right))
    return std::nullopt;
  const Eigen::Vector3d axis = skeleton[jb] - skeleton[ja];
  const Eigen::Vector3d across = skeleton[left] - skeleton[right];
  const double axis_norm = axis.norm(), across_norm = across.norm();
  if (!(axis_norm > 0) || !(across_norm > 0)) return std::nullopt;
  const Eigen::Vector3d z = axis / axis_norm;
  const Eigen::Vector3d w = across / across_norm - z.dot(across / across_norm) * z;
  if (!(w.norm() > 1e-6)) return std::nullopt;
  return Eigen::Vector3d(w.normalized());
}

std::optional<Eigen::Vector3d> PartReferenceDirection(const Skeleton& skeleton, BodyPart part) {
  if (part == BodyPart::kUpperTorso || part == BodyPart::kLowerTorso)
    return PartWidthDirection(skeleton, part);
  const bool leg = part == BodyPart::kLeftThigh || part == BodyPart::kLeftShin ||
                   part == BodyPart::kRightThigh || part == BodyPart::kRightShin;
  const Joint left = leg ? Joint::kLeftHip : Joint::kLeftShoulder;
  const Joint right = leg ? Joint::kRightHip : Joint::kRightShoulder;
  const auto [ja, jb] = PartJoints(part);
  for (Joint j : {ja, jb, left, right, Joint::kNeck, Joint::kWaist})
    if (!skeleton.Has(j)) return std::nullopt;
  const Eigen::Vector3d axis = skeleton[jb] - skeleton[ja];
  const Eigen::Vector3d across = skeleton[left] - skeleton[right];
  const Eigen::Vector3d forward = across.cross(skeleton[Joint::kNeck] - skeleton[Joint::kWaist]);
  if (!(axis.norm() > 0) || !(across.norm() > 0) || !(forward.norm() > 0)) return std::nullopt;
  const Eigen::Vector3d a = across.normalized(), f = forward.normalized();
  Eigen::Vector3d h;
  switch (part) {
    case BodyPart::kHead: h = f; break;
    case BodyPart::kLeftUpperArm:
    case BodyPart::kLeftForearm: h = -f - a; break;
    case BodyPart::kRightUpperArm:
    case BodyPart::kRightForearm: h = -f + a; break;
    case BodyPart::kLeftThigh:
    case BodyPart::kLeftShin: h = -a; break;
    default: h = a; break;
  }
  h.normalize();
  const Eigen::Vector3d z = axis.normalized();
  const Eigen::Vector3d across_axis = h - h.dot(z) * z;
  if (!(across_axis.norm() >= 0.1)) return std::nullopt;
  return Eigen::Vector3d(across_axis.normalized());
}

std::optional<Cylinder> PoseCylinder(const Skeleton& skeleton, BodyPart part,
                                     const RadiusRatios& ratios, const PartExtensions& extensions,
                                     const PartShapes& shapes) {
  const double ratio = ratios[Index(part)];
  const double extension = extensions[Index(part)];
  REENACT_CHECK(std::isfinite(ratio) && ratio >= 0, "radius ratio must be finite and >= 0");
  REENACT_CHECK(std::isfinite(extension) && extension >= 0,
                "part extension must be finite and >= 0");
  if (!skeleton.HasPart(part)) return std::nullopt;
  const auto [ja, jb] = PartJoints(part);
  Cylinder c{skeleton[ja], skeleton[jb], 0.0};
  const double length = c.Length();
  if (!(length >= kMinBoneLength)) return std::nullopt;
  c.radius = length * ratio;
  if (extension > 0) {
    const Eigen::Vector3d outward = EndJoint(part) == ja ? Eigen::Vector3d(c.a - c.b)
                                                         : Eigen::Vector3d(c.b - c.a);
    (EndJoint(part) == ja ? c.a : c.b) += extension * outward;
  }
  c.shape = shapes[Index(part)];
  REENACT_CHECK(c.shape.IsValid(), "part shape values must be finite and > 0 (PartShape::IsValid)");
  for (int end = 0; end < 2; ++end) {
    const int k = end == 0 ? 0 : kShapeRings - 1;
    c.shape.cap_depth[end] = c.shape.round_end[end] ? c.radius *
                                                          std::sqrt(c.shape.width[k] * c.shape.depth[k]) /
                                                          c.Length()
                                                    : 0.0;
  }
  const PartSurface& surface = c.shape.surface;
  if (!surface.IsEmpty()) {
    c.width_direction = PartReferenceDirection(skeleton, part);
    if (c.width_direction) return c;
    c.shape.surface = {};
  }
  if (!c.shape.IsCircular()) {
    c.width_direction = PartWidthDirection(skeleton, part);
    if (!c.width_direction) {
      for (int k = 0; k < kShapeRings; ++k)
        c.shape.width[k] = c.shape.depth[k] = std::sqrt(c.shape.width[k] * c.shape.depth[k]);
    }
  }
  return c;
}

std::array<std::optional<Cylinder>, kBodyPartCount> PoseCylinders(const Skeleton& skeleton,
                                                                  const RadiusRatios& ratios,
                                                                  const PartExtensions& extensions,
                                                                  const PartShapes& shapes) {
  std::array<std::optional<Cylinder>, kBodyPartCount> out;
  for (int p = 0; p < kBodyPartCount; ++p)
    out[p] = PoseCylinder(skeleton, static_cast<BodyPart>(p), ratios, extensions, shapes);
  return out;
}

}  // namespace reenact
