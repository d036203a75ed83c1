#pragma once
// The rough body model of the thesis: one cylinder per body part, whose axis runs between the
// part's two joints and whose radius is a fixed ratio of the axis length:
//   r_{k,a,b} = ||s_{k,a} - s_{k,b}|| * r_{a,b}      (thesis Sec. 3.3.3)
// radius_ratio stores r_{a,b} = radius / bone length (the thesis's "w / ||s_a - s_b||" read
// with w the rectangle's half width, i.e. the cylinder's radius; see radius_fit.h).

#include <array>
#include <optional>

#include <Eigen/Core>

#include "common/skeleton/skeleton.h"

namespace reenact {

using RadiusRatios = std::array<double, kBodyPartCount>;

// Extension of each part past its end joint (issue 9, a closer shape: hands, feet and the top
// of the head lie past the last joint of their part), as a ratio of the bone length
// ||s_a - s_b||, >= 0. The end joint is EndJoint(part): the head joint for the head (whose
// axis runs head -> neck), joint b for every other part. All zeros (the default) is the
// thesis's cylinder between the two joints. Fitted by extension_fit.h.
using PartExtensions = std::array<double, kBodyPartCount>;

// The joint past which a part is extended: Joint::kHead for the head, PartJoints(part).second
// otherwise.
Joint EndJoint(BodyPart part);

// Typical adult proportions (radius / bone length), used where a part could not be fitted.
RadiusRatios DefaultRadiusRatios();

struct Cylinder {
  Eigen::Vector3d a;  // axis end at joint a (PartJoints(part).first), same frame as the skeleton
  Eigen::Vector3d b;  // axis end at joint b
  double radius = 0;  // metres

  double Length() const { return (b - a).norm(); }
};

// Bones shorter than this (metres) are degenerate: their cylinder is not posed.
inline constexpr double kMinBoneLength = 1e-4;

// Cylinder of one part posed from a skeleton; nullopt if a joint is missing or the bone is
// shorter than kMinBoneLength. With extensions, the axis end at EndJoint(part) moves outwards
// along the axis by extensions[part] * bone length; the radius stays bone length * ratio.
// Preconditions (CHECK): ratio and extension finite and >= 0.
std::optional<Cylinder> PoseCylinder(const Skeleton& skeleton, BodyPart part,
                                     const RadiusRatios& ratios,
                                     const PartExtensions& extensions = {});

// All parts, indexed by Index(BodyPart).
std::array<std::optional<Cylinder>, kBodyPartCount> PoseCylinders(
    const Skeleton& skeleton, const RadiusRatios& ratios, const PartExtensions& extensions = {});

}  // namespace reenact
