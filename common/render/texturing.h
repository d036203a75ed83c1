#pragma once
// Texturing rules of the cylinder body model with several ranked texture candidates per
// cylinder (issue 9), shared rule for rule by the GL renderer
// (viewer-client/render/renderer.h) and the CPU reference renderer (reference_renderer.h).
//
// A cylinder carries at most kMaxTextureCandidates candidates, the ranked ones and then the
// fallback ones (below), each a stored frame's crop with its stored_from_viewer (thesis Eq. 16)
// and a weight >= 0, plus the body part it models. Per fragment at the viewer-frame surface
// point p*, candidate i:
//   - maps p* to p_n = stored_from_viewer_i p* (divided by w) and projects it with the crop
//     camera's intrinsics to (u, v) (OpenCV pixel centres at integers);
//   - is *usable* when p_n.z > 0, (u, v) lies in [-0.5, w - 0.5] x [-0.5, h - 0.5] and the
//     bilinear mask (alpha) sample there is >= 0.5; its colour c_i is then the premultiplied
//     bilinear sample divided by its alpha (the single-texture rule of the thesis renderer);
//   - is *visible* when usable and, at the nearest texel (x, y) = (clamp(floor(u + 0.5),
//     0, w - 1), clamp(floor(v + 0.5), 0, h - 1)), (a) the crop's part-label map holds
//     PartLabel(part) and (b) the stored depth d (metres) is 0 (no reading: (b) passes) or
//     |d - p_n.z| <= depth_tolerance_m. A crop without a part-label map has no visible
//     point (no evidence of visibility: the modes below fall back to the usable rule).
// Modes:
//   - kFirst: candidate 0's colour where usable, else the fragment is discarded; the other
//     candidates are ignored (the thesis renderer).
//   - kFirstVisible (occlusion-aware): the first visible candidate in rank order gives the
//     colour; if none is visible, the first usable one; else discard.
//   - kBlendVisible: sum_i w_i c_i / sum_i w_i over the visible candidates (weights
//     renormalised over them); where that sum of weights is 0 (none visible, or all their
//     weights 0), as kFirstVisible.
// Fallback candidates (the visible modes; after every ranked candidate, which the modes above
// use alone): where those rules take the first usable ranked candidate because none is
// visible, and that candidate's label at (x, y) is another part's (its texel shows what stood
// in front of this part), the first visible fallback candidate colours the fragment instead,
// if any. So fallbacks never add to the silhouette (a fragment no ranked candidate can colour
// is still discarded) and never replace a texel labelled as this part whose depth alone
// disagrees (the rough model's depth, more often than an occluder).
// A cylinder with no candidate is drawn in its flat colour.
// Relighting (common/texture/subject_light.h), where the frame's light is not zero: each
// usable candidate's colour c_i is taken as
//   c_i * SubjectShade(n_i, light) / SubjectShade(n_i, stored_light_i)
// before any mode uses it, with light the subject light as the viewer sees it now and
// stored_light_i the same light as candidate i's stored frame saw it, both in the viewer frame
// (stored_light_i = R_i^T L_i, R_i the rotation of stored_from_viewer_i and L_i the light in
// that stored sensor frame). n_i is the stored surface's own normal carried to the viewer with
// the texture, R_i^T n_s, n_s the crop's normal map at the nearest texel (x, y) above where it
// is not zero (common/texture/subject_light.h DepthNormalMap); else n, the unit surface
// normal of the drawn model at p* (viewer frame). A zero light (the default) leaves every
// colour as it is.

namespace reenact {

// Ranked candidates and fallback candidates (weight 0, reenactment.h) together.
inline constexpr int kMaxTextureCandidates = 6;

// Default of depth_tolerance_m. The cylinders are rough: over the labelled subject pixels of
// every 10th stored frame of the synthetic CesiumMan clips, |stored depth - depth of the
// posed cylinder's front surface| has median 1.4 / 1.7 cm and 90th percentile 4.7 / 7.1 cm
// (turn-and-kick / walk-handheld); 6 cm accepts 93 / 88 % of those front-surface pixels
// while rejecting points 6 cm or more behind the surface, e.g. the far side of a limb (median
// cylinder diameter 9 cm) or a part hidden behind another by more than that.
inline constexpr double kDefaultDepthToleranceM = 0.06;

enum class TexturingMode { kFirst = 0, kFirstVisible = 1, kBlendVisible = 2 };

}  // namespace reenact
