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

// Cross-sections along a part's drawn axis (issue 9, a closer shape: radius rings and an
// elliptic torso). kShapeRings rings at t_k = k / (kShapeRings - 1) of the drawn axis, t = 0 at
// the cylinder's a end and t = 1 at its b end (past the end joint where extended). Ring k is an
// ellipse with semi-axes width[k] * radius along the cylinder's width direction and
// depth[k] * radius along axis x width, in the right-handed frame (x width, y depth, z the
// axis a -> b). Between two rings the surface is linear in t (a ruled surface, drawn
// tessellated). All ones (the default): the thesis's cylinder. Values are finite and > 0.
inline constexpr int kShapeRings = 5;

// A fitted surface on top of the rings (issue 57, a body surface fitted from depth): a height
// map in the part's own frame, radial[k][j] the factor by which ring k's ellipse is scaled at
// the angle phi_j = 2 pi j / angles around the axis, measured in the frame's (x, y) plane from
// x (the part's reference direction, PartReferenceDirection) towards y = axis x x, in the
// ellipse's own parameter: the surface point at (ring k, phi) is
//   s(k, phi) (width[k] cos phi, depth[k] sin phi, t_k)  (unit frame, times the radius in x, y)
// with s periodic and linear in phi between the nodes phi_j, linear in t between the rings.
// angles 0 (the default): no surface, s = 1 everywhere (the rings alone). Fitted by
// surface_fit.h, whose rule chooses `angles` per part from its data.
inline constexpr int kMaxSurfaceAngles = 16;

struct PartSurface {
  int angles = 0;  // 0 (none) or in [3, kMaxSurfaceAngles]
  std::array<std::array<double, kMaxSurfaceAngles>, kShapeRings> radial{};  // finite, > 0

  bool IsEmpty() const { return angles == 0; }
  // s(k, phi): node values of ring k, periodic and linear in phi; 1 when empty.
  double FactorAt(int k, double phi) const;
};

struct PartShape {
  std::array<double, kShapeRings> width{1, 1, 1, 1, 1};
  std::array<double, kShapeRings> depth{1, 1, 1, 1, 1};
  PartSurface surface{};
  // Rounded ends (issue 57: parts meet without gaps at the joints): whether the a and b ends
  // are closed by half ellipsoids over their end rings instead of flat discs, each as deep
  // along the axis as the end ring's mean radius (r sqrt(W D)); set by the surface fit for the
  // ends at the limbs' joints. cap_depth is that depth as a fraction of the drawn axis length,
  // set by PoseCylinder from round_end (0 for a flat end); the renderers draw it
  // (cylinder_mesh.h).
  std::array<bool, 2> round_end{false, false};
  std::array<double, 2> cap_depth{0, 0};

  bool IsCylinder() const;  // every ring 1 x 1, no surface, flat ends
  bool IsCircular() const;  // width[k] == depth[k] at every ring (tapered at most), no surface
  // Every ring value finite and > 0, the surface's angles 0 or in [3, kMaxSurfaceAngles] with
  // its factors finite and > 0, the cap depths finite and >= 0.
  bool IsValid() const;
  // Largest distance of ring k's drawn points from the axis, in radii: max(width, depth)
  // times the largest surface factor of the ring (1 without a surface).
  double RingReach(int k) const;
};

// The value at axis fraction t (clamped to [0, 1]) of a ring profile (width or depth), linear
// between the rings at t_k = k / (kShapeRings - 1).
double RingValueAt(const std::array<double, kShapeRings>& rings, double t);

// Indexed by Index(BodyPart). Fitted by cross_section_fit.h.
using PartShapes = std::array<PartShape, kBodyPartCount>;

struct Cylinder {
  Eigen::Vector3d a;  // axis end at joint a (PartJoints(part).first), same frame as the skeleton
  Eigen::Vector3d b;  // axis end at joint b
  double radius = 0;  // metres
  PartShape shape{};  // cross-sections (default: the plain cylinder)
  // Unit vector orthogonal to the axis along which the shape's width runs; nullopt: any
  // (the renderers' helper rule, cylinder_mesh.h). Set by PoseCylinder for an elliptic part.
  std::optional<Eigen::Vector3d> width_direction{};

  double Length() const { return (b - a).norm(); }
};

// Bones shorter than this (metres) are degenerate: their cylinder is not posed.
inline constexpr double kMinBoneLength = 1e-4;

// The body's left-to-right direction a part's width runs along: l_shoulder - r_shoulder for
// the upper torso, l_hip - r_hip for the lower torso, made orthogonal to the part's axis and
// unit; nullopt for every other part, when a joint is missing, or when that line is within
// 1e-6 (sine of the angle) of parallel to the axis.
std::optional<Eigen::Vector3d> PartWidthDirection(const Skeleton& skeleton, BodyPart part);

// The direction, fixed to the body, from which a part's surface angles are measured (made
// orthogonal to the part's axis and unit): PartWidthDirection for the torso parts; for the
// others a direction in the body's frame (across = l_shoulder - r_shoulder for the head and
// arms, l_hip - r_hip for the legs; forward = across x (neck - waist), the way the chest
// faces) chosen where the part's axis rarely points, so that the frame turns with the part
// and never flips in common poses: the head forward; an arm back and across the body (the
// left arm along -forward - across, the right along -forward + across); a leg across
// towards the other leg (left -across, right +across). nullopt when a joint is missing or
// the direction is within 0.1 (sine of the angle) of parallel to the axis.
std::optional<Eigen::Vector3d> PartReferenceDirection(const Skeleton& skeleton, BodyPart part);

// Cylinder of one part posed from a skeleton; nullopt if a joint is missing or the bone is
// shorter than kMinBoneLength. With extensions, the axis end at EndJoint(part) moves outwards
// along the axis by extensions[part] * bone length; the radius stays bone length * ratio.
// With shapes, the cylinder carries shapes[part]; a part that is not IsCircular() gets
// width_direction = PartWidthDirection(skeleton, part), and where that is nullopt it is drawn
// circular instead: width[k] = depth[k] = sqrt(width[k] depth[k]) (same cross-section area).
// A part with a surface gets width_direction = PartReferenceDirection(skeleton, part) (for
// the torso parts the same as PartWidthDirection); where that is nullopt the surface is
// dropped (the rings alone are drawn, as above).
// Preconditions (CHECK): ratio and extension finite and >= 0; shape values finite and > 0.
std::optional<Cylinder> PoseCylinder(const Skeleton& skeleton, BodyPart part,
                                     const RadiusRatios& ratios,
                                     const PartExtensions& extensions = {},
                                     const PartShapes& shapes = {});

// All parts, indexed by Index(BodyPart).
std::array<std::optional<Cylinder>, kBodyPartCount> PoseCylinders(
    const Skeleton& skeleton, const RadiusRatios& ratios, const PartExtensions& extensions = {},
    const PartShapes& shapes = {});

}  // namespace reenact
