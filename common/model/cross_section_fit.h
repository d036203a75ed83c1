#pragma once
// Part shapes (cylinder_model.h's PartShape; issue 9, a closer shape: radius rings and an
// elliptic torso) from a few stored frames: how wide the subject's silhouette is at each ring
// of each part's drawn axis.
//
// Per frame, every part is posed as it is drawn (PoseCylinder with the part extensions; the
// rings sit at t_k = k / (kShapeRings - 1) of the drawn axis a -> b).
//
// Pixels to parts (part_pixel_assignment.h). Each subject pixel goes to the part whose
// projected drawn axis is nearest, distances measured in each part's projected radius (a wide
// torso keeps its pixels next to a thin arm's axis) and, where the pixel has a depth reading,
// as the distance from the visible half of the part's plain cylinder (a forearm in front of
// the belly keeps its pixels; an arm's root behind the torso's edge is not torso). Segments
// reach past their ends by the near rim of their end discs (perspective lifts the rim of a
// shoulder or of the lower torso's top past the projected joint; those pixels stay with their
// part instead of widening the neighbour's end). A pixel is then counted for its part only
// within the largest allowed half-width of the axis (max_ratio * radius seen at the axis's
// depth, plus 10% and 2 pixels) and with its reading (if any) within depth_tolerance_m +
// max_ratio * radius of the axis's depth there.
//
// A ring is measured on a slice of the part's pixels around its position t_m along the axis
// (half_slice of the drawn axis to either side, at least 1.5 pixels), cut into 1-pixel lines
// across the projected axis. On each line the part's pixels are split into runs where
// background lies between them (gaps of other parts' or uncounted pixels, an occluder in
// front, are bridged); the run that holds the axis, or else lies nearest to it, is the part's,
// and its outermost pixels, each 0.5 pixel further out, are the silhouette's two edges. The
// extent, not the pixel count (area / length), is used because it is unaffected by holes in
// the silhouette (occluders in front, mask holes, depth-test rejections) and by the joint
// lying off the silhouette's centre line. Against the extent's weakness (a neighbour that
// touches the part), an edge counts only where the silhouette really ends: the pixel one step
// further out across the axis must be background, the part's own, or more than
// depth_tolerance_m behind the edge pixel (the part occludes it); a neighbour at the same
// depth, an occluder in front or the image border (a clipped view) make the line measure
// nothing. A ring needs min_lines lines with both edges valid; its edge offsets are the
// medians over those lines.
//
// Pixels to metres, exact under perspective: the camera ray through an edge pixel (at the
// ring's position) and the part's 3D axis span the silhouette's tangent plane, which is
// parallel to the axis; the distance from the axis to that plane is the cross-section's
// support function h(n) in the plane's normal n (n orthogonal to the axis). For an ellipse
// with semi-axes W r (width direction w) and D r (depth direction d = axis x w):
//   h(n) = r sqrt(W^2 (n.w)^2 + D^2 (n.d)^2)
// (the orthographic form h = r sqrt(W^2 sin^2 theta + D^2 cos^2 theta), theta the angle
// between the viewing ray and w, is this with n orthogonal to the ray). A ring's measurement in
// a frame is q = (h_+ + h_-) / (2 r), the mean of the two sides' signed distances (an axis off
// the silhouette's centre cancels to first order). The scale comes from the skeleton's axis,
// not from depth readings: the drawn shape surrounds that axis, so its reprojected silhouette
// then matches the stored one, and depth holes do not matter. A frame measures nothing for a
// part when a joint is missing, the bone is shorter than kMinBoneLength, an axis end is
// closer to the camera plane than max_ratio * radius (or behind it), or the axis is
// foreshortened below min_axis_scale of f / z at the ring (it points at the camera and its
// end caps make the silhouette).
//
// End rings: t = 0 and t = 1 overlap the neighbouring part (neck, shoulder, hip, a joint), so
// they are measured at the inset t = end_inset and 1 - end_inset and by default take that
// value (a taper of s over the part is then off by s * end_inset at the ends). With
// extrapolate_end_rings, the end ring takes the value that, interpolated linearly with its
// inner neighbour as the drawn surface is, reproduces the inset measurement:
// v_0 = v_1 + (m - v_1) / w, w = (t_1 - t_in) / t_1 (mirrored at t = 1), which amplifies the
// inset measurement's error (and any overlap it still catches) by 1 / w = 2.5 at the default.
//
// Over frames, per ring:
// - Head and limbs: circular, width = depth = the median of q.
// - Upper and lower torso (elliptic, width along PartWidthDirection): each frame gives
//   q^2 = W^2 c + D^2 (1 - c), c the mean of (n.w)^2 over its two edges: a line in c with
//   intercept D^2 and slope W^2 - D^2, fitted robustly (Theil-Sen: the median slope over
//   pairs of one frontal and one side frame, as below, whose c differ by at least
//   min_pair_spread; the intercept is the median of q^2 - slope c). W and D separate only
//   when at least min_frames_each_way frames see the ring frontally (c >= elliptic_split,
//   within 45 degrees of the front or back at the default) and as many from the side
//   (c < elliptic_split). A ring whose frames do not separate W and D borrows one of them
//   from the part's rings that did (interpolated between them): if most of its frames are
//   frontal, D (a torso's depth varies less along it than its width, which the shoulders
//   widen), and W is the median over its frontal frames of sqrt((q^2 - D^2 (1 - c)) / c);
//   else W, and D is the median over its side frames. Where no ring of the part separated
//   (e.g. every frame frontal), the ring is circular with the median q (the width frontal
//   views show).
// - Ratios are clamped to [min_ratio, max_ratio]. A ring no frame measured takes the value
//   interpolated linearly between the nearest measured rings (copied beyond the outermost);
//   a part no frame measured keeps the plain cylinder (all ones) and fitted false.

#include <array>
#include <optional>
#include <span>

#include "common/model/cylinder_model.h"
#include "common/model/extension_fit.h"

namespace reenact {

struct CrossSectionFitOptions {
  double end_inset = 0.15;             // (0, 0.25): t at which the end rings are measured
  bool extrapolate_end_rings = false;  // see above
  double half_slice = 0.05;            // (0, 0.125]: slice half-length, fraction of the axis
  int min_lines = 2;                   // >= 1: valid lines a ring measurement needs
  double min_axis_scale = 0.5;         // (0, 1]: least |d pixel / d axis| / (f / z) measured at
  double depth_tolerance_m = 0.05;     // >= 0: depth test slack and least occlusion gap, m
  double depth_scale_m = 0.001;        // metres per depth unit, > 0
  double min_ratio = 0.4;              // (0, 1]: least ring ratio
  double max_ratio = 2.5;              // >= 1: largest ring ratio (and the pixel search band)
  double elliptic_split = 0.5;         // (0, 1): frontal (c >= split) vs side (c < split)
  int min_frames_each_way = 2;         // >= 1
  double min_pair_spread = 0.25;       // (0, 1]: least c difference of a Theil-Sen pair

  void Check() const;
};

// The same stored frame as the extension fit's: skeleton in its sensor frame; camera, mask
// (255 subject) and depth (registered, may be empty: no depth test) on one image grid.
using CrossSectionFitFrame = ExtensionFitFrame;

// One ring of one part in one frame.
struct RingMeasurement {
  double t = 0;           // where along the drawn axis it was measured (end rings: inset)
  double radius_m = 0;    // the posed cylinder's radius r in this frame
  double half_width = 0;  // q = (h_+ + h_-) / (2 r), > 0
  // (n.w)^2 of each edge's tangent-plane normal, where the frame has a width direction for
  // the part (torso parts); nullopt otherwise.
  std::optional<std::array<double, 2>> width_weight;
};

using PartRingMeasurements = std::array<std::optional<RingMeasurement>, kShapeRings>;
using CrossSectionMeasurements = std::array<PartRingMeasurements, kBodyPartCount>;

// Every ring of every part measurable in one frame (see above).
// Preconditions (CHECK): options valid; the frame's pointers set; mask 1-channel of the
// camera's size; depth empty or 1-channel of the mask's size; ratios and extensions finite
// and >= 0.
CrossSectionMeasurements MeasureCrossSections(const CrossSectionFitFrame& frame,
                                              const RadiusRatios& ratios,
                                              const PartExtensions& extensions,
                                              const CrossSectionFitOptions& options = {});

struct CrossSectionFitResult {
  PartShapes shape{};                                 // all ones where not fitted
  std::array<bool, kBodyPartCount> fitted{};          // some frame measured some ring
  std::array<bool, kBodyPartCount> elliptic{};        // W and D separated at some ring
  std::array<int, kBodyPartCount> frames_measured{};  // frames that measured some ring
};

// The fit over frames (any number; none: every part the plain cylinder, not fitted).
CrossSectionFitResult FitCrossSections(std::span<const CrossSectionFitFrame> frames,
                                       const RadiusRatios& ratios, const PartExtensions& extensions,
                                       const CrossSectionFitOptions& options = {});

// How well shapes reproduce the frames' silhouettes: per part, the mean over frames and
// measured rings of |h_shape - h_measured| (metres; h the half-width as measured above,
// h_shape from the shape at the ring's t, drawn circular as sqrt(W D) where the frame has no
// width direction). In-sample when the shapes were fitted on the same frames.
struct CrossSectionError {
  std::array<double, kBodyPartCount> mean_abs_m{};  // 0 where samples is 0
  std::array<int, kBodyPartCount> samples{};
  double mean_abs_m_all = 0;  // over every sample of every part; 0 if none
  int samples_all = 0;
};

CrossSectionError MeasureCrossSectionError(std::span<const CrossSectionFitFrame> frames,
                                           const RadiusRatios& ratios,
                                           const PartExtensions& extensions,
                                           const PartShapes& shapes,
                                           const CrossSectionFitOptions& options = {});

}  // namespace reenact
