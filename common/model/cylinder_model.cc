#include "common/model/cylinder_model.h"

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

std::optional<Cylinder> PoseCylinder(const Skeleton& skeleton, BodyPart part,
                                     const RadiusRatios& ratios, const PartExtensions& extensions) {
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
  return c;
}

std::array<std::optional<Cylinder>, kBodyPartCount> PoseCylinders(
    const Skeleton& skeleton, const RadiusRatios& ratios, const PartExtensions& extensions) {
  std::array<std::optional<Cylinder>, kBodyPartCount> out;
  for (int p = 0; p < kBodyPartCount; ++p)
    out[p] = PoseCylinder(skeleton, static_cast<BodyPart>(p), ratios, extensions);
  return out;
}

}  // namespace reenact
