#include "common/model/cylinder_model.h"

#include <algorithm>
#include <cmath>

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

bool PartShape::IsCylinder() const {
  for (int k = 0; k < kShapeRings; ++k)
    if (width[k] != 1.0 || depth[k] != 1.0) return false;
  return true;
}

bool PartShape::IsCircular() const { return width == depth; }

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
  for (int k = 0; k < kShapeRings; ++k)
    REENACT_CHECK(std::isfinite(c.shape.width[k]) && c.shape.width[k] > 0 &&
                      std::isfinite(c.shape.depth[k]) && c.shape.depth[k] > 0,
                  "part shape rings must be finite and > 0");
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
