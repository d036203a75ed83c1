#pragma once
// Part surfaces (cylinder_model.h's PartSurface; issue 57, a body surface fitted from depth):
// each part's radius as a function of the angle around its axis and the ring along it, from
// the depth points of a few stored frames, only as fine as those points support.
//
// Points. Per frame, every part is posed as it is drawn with the rings fitted before
// (PoseCylinder with the extensions and shapes), in its own frame: ViewerFromUnitCylinder with
// the body-fixed PartReferenceDirection as x (a part without one measures nothing in that
// frame). Every subject pixel with a depth reading is back-projected to the sensor-frame
// point X and taken to each part's unit frame, q = unit_from_sensor X; where 0 <= q.z <= 1
// its normalised radial coordinate is e = (q.x / W(t), q.y / D(t)), t = q.z, W and D the
// ring profiles (RingValueAt): rho = |e|, phi = atan2(e.y, e.x), so rho = 1 on the ring
// surface and rho = s(t, phi) on the fitted one. The point goes to the part whose ring surface
// lies nearest, |rho - 1| r sqrt(W D) metres, and is kept when rho lies in [min_factor,
// max_factor]: a point between two parts (a hand against the hip) goes to the one whose
// surface it lies on.
//
// Cells. For `angles` = A, node (k, j) of ring k at t_k = k / (kShapeRings - 1) and angle
// phi_j = 2 pi j / A collects the points nearest to it (|t - t_k| <= 1 / (2 (kShapeRings -
// 1)), |phi - phi_j| <= pi / A); a node with at least min_points points from at least
// min_frames frames takes their median rho (robust to stray points and to depth noise). Holes:
// a node not measured takes the mean of its two angular neighbours where both were measured,
// then the mean of the same node on the neighbouring rings where any was, and otherwise 1,
// the ring fit (so a side no frame saw stays at the rings, which fit its silhouette).
//
// Resolution. For each part the candidates 0 (the rings alone) and each of angle_choices
// are fitted on half of the frames (alternate frames) and scored on the other half's points,
// then the halves swapped: the held-out error is the mean over those points of
// |rho - rho_model(t, phi)| r sqrt(W D) (metres; rho_model linear between the rings and the
// nodes, as drawn). A finer candidate is chosen only where it lowers the held-out error by
// more than min_gain of the coarser one's (a part seen from one side only, seen small, or too
// noisy for detail stays coarse). The chosen resolution is then fitted on all frames.
//
// Joints. The result also rounds the limbs' ends at their joints (PartShape::round_end: both
// ends of the upper arms and thighs, the elbow and knee ends of the forearms and shins), so
// that two parts meeting at a joint bent by any angle leave no gap: each rounded end covers
// the ball of its end ring's radius about the joint on its side of the end plane, and the
// wedge a bend opens outside both parts lies within those balls.

#include <array>
#include <span>
#include <vector>

#include "common/model/cylinder_model.h"
#include "common/model/extension_fit.h"

namespace reenact {

struct SurfaceFitOptions {
  std::vector<int> angle_choices = {4, 8, 16};  // increasing, each in [3, kMaxSurfaceAngles]
  int min_points = 12;         // >= 1: points a node needs
  int min_frames = 2;          // >= 1: frames those points come from
  double min_factor = 0.5;     // (0, 1]: least rho kept (and least factor)
  double max_factor = 3.0;     // >= 1: largest rho kept (and largest factor)
  double min_gain = 0.05;      // [0, 1): relative held-out gain a finer resolution needs
  int pixel_step = 1;          // >= 1: every pixel_step-th pixel in x and y is used
  double depth_scale_m = 0.001;  // metres per depth unit, > 0

  void Check() const;
};

using SurfaceFitFrame = ExtensionFitFrame;

struct SurfaceFitResult {
  PartShapes shape{};  // the given shapes with the chosen surfaces and the rounded ends
  std::array<int, kBodyPartCount> angles{};  // chosen resolution, 0: the rings alone
  std::array<int, kBodyPartCount> points{};  // points assigned over all frames
  // Held-out errors (metres) of the rings alone and of the chosen resolution; scored false
  // (and both 0) for a part whose points do not fill both halves.
  std::array<bool, kBodyPartCount> scored{};
  std::array<double, kBodyPartCount> rings_error_m{};
  std::array<double, kBodyPartCount> chosen_error_m{};
};

// The fit over frames (any number; none or too few points: every part keeps its rings).
// Preconditions (CHECK): options valid; each frame's pointers set; mask 1-channel of the
// camera's size; depth empty (the frame gives no points) or of the mask's size; ratios and
// extensions finite and >= 0; shapes without surfaces.
SurfaceFitResult FitPartSurfaces(std::span<const SurfaceFitFrame> frames,
                                 const RadiusRatios& ratios, const PartExtensions& extensions,
                                 const PartShapes& shapes, const SurfaceFitOptions& options = {});

}  // namespace reenact
