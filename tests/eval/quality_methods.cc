#include "tests/eval/quality_methods.h"

#include "viewer-client/play/texturing_presets.h"

namespace reenact::eval {
namespace {

using viewer::TextureSelection;
using viewer::TexturingOptions;

// The thesis's pose (the stored skeleton) or, on the steady clip, the steady track's, drawn
// with `texturing`; cylinders only.
QualityMethod Method(std::string name, std::string summary, bool steady,
                     const TexturingOptions& texturing) {
  QualityMethod method{std::move(name), std::move(summary), {}, texturing.shape, steady};
  method.build = [steady, texturing](const viewer::Reenactment& clip, int k,
                                     const PinholeCamera& camera,
                                     const Eigen::Isometry3d& viewer_from_world,
                                     const std::function<int(int)>& texture_for_frame,
                                     PartSelectionHistory* history) {
    const Skeleton& pose = steady ? clip.SteadySkeletonInWorld(k) : clip.frame(k).skeleton_in_world;
    viewer::ReenactedFrame frame =
        clip.BuildPosed(k, pose, camera, viewer_from_world, texture_for_frame, texturing, history);
    frame.draw.bones.clear();
    frame.draw.floor.reset();
    frame.draw.background = nullptr;
    return frame;
  };
  return method;
}

TexturingOptions Preset(std::string_view name) { return viewer::TexturingPreset(name).value(); }

}  // namespace

const std::vector<QualityMethod>& QualityMethods() {
  static const std::vector<QualityMethod> methods = {
      Method("thesis",
             "the thesis exactly: whole-skeleton Eq. 5 selects one stored frame per output frame, "
             "Eq. 6-16 map every cylinder onto it, no occlusion handling",
             false, {}),
      Method(
          "steady",
          "thesis + steady motion: the posed skeleton from the clip's steady track (skeletons the "
          "capture flagged interpolated across from their neighbours, every joint One Euro "
          "filtered: min cutoff 1 Hz, beta 8 Hz per m/s, derivative cutoff 1 Hz, "
          "forward and backward; common/filter/steady_motion.h), and every stored frame's "
          "skeleton from it as well, so that the pose shown and the frames it is textured from "
          "agree; selection and mapping as the thesis",
          true, {}),
      Method("per-part",
             "thesis + per-part selection: each body part textured from its own best stored frame, "
             "ranked by the part's view and the pose of the part and its neighbours "
             "(common/texture/part_selection.h), among frames where the part lies inside the crop",
             false, Preset("per-part")),
      Method("occlusion",
             "per-part + occlusion-aware texturing: the 3 best frames per part, each fragment "
             "coloured by the first in which its point is visible (the stored part-label map shows "
             "the same part and the stored depth agrees; common/render/texturing.h)",
             false, Preset("occlusion")),
      Method(
          "blend",
          "occlusion + blending: each fragment the weighted mean of the visible candidates "
          "(unstructured-lumigraph weights from the per-part cost, which holds viewing-angle and "
          "pose difference), with hysteresis 0.1 on the chosen frames",
          false, Preset("blend")),
      Method(
          "shape",
          "blend + a closer shape: the head, forearms and shins extended past their end joints "
          "(top of the head, hands, feet) by ratios of the bone length fitted at load from the "
          "stored masks and depth (common/model/extension_fit.h), in the drawn cylinders and the "
          "stored part-label maps",
          false, Preset("shape")),
      Method("profile",
             "shape + radius rings and an elliptic torso: each part's cross-section varies along "
             "its axis through 5 rings, the torso's is an ellipse across the shoulders and hips, "
             "fitted at load from the stored silhouettes of up to 25 frames "
             "(common/model/cross_section_fit.h)",
             false, Preset("profile")),
      Method("relit",
             "profile + relighting: each stored colour re-shaded from the normal it was recorded "
             "at to the normal shown, under one directional light plus ambient fitted at load "
             "from the colours and depth normals of up to 25 stored frames "
             "(common/texture/subject_light.h)",
             false, Preset("relit")),
      Method("fallback",
             "relit + fallback candidates: per part, up to 3 more stored frames chosen to see what "
             "of the part's facing half the 3 ranked ones do not (a 12 x 5 grid of its surface, "
             "each cell tested against every stored frame's part labels and depth at load; "
             "common/texture/part_coverage.h), drawn only where no ranked candidate is visible and "
             "the first usable one's texel is labelled as another part",
             false, Preset("fallback")),
      Method("surface",
             "fallback + a fitted surface: each part's radius varies around its axis as well as "
             "along it, a height map of up to 16 angles x 5 rings in the part's body-fixed frame, "
             "fitted at load from the depth of up to 25 stored frames at the resolution that "
             "predicts held-out frames' points best (common/model/surface_fit.h), and the limbs' "
             "ends rounded at their joints so that bent joints leave no gap",
             false, Preset("surface")),
      Method("all", "fallback + steady motion: every step of issue 9 together", true,
             Preset("fallback")),
  };
  return methods;
}

Expected<const QualityMethod*> FindQualityMethod(std::string_view name) {
  std::string known;
  for (const QualityMethod& m : QualityMethods()) {
    if (m.name == name) return &m;
    known += (known.empty() ? "" : ", ") + m.name;
  }
  return MakeError("usage", "unknown method '" + std::string(name) + "'; known methods: " + known);
}

Expected<std::vector<const QualityMethod*>> FindQualityMethods(const std::vector<std::string>& names) {
  std::vector<const QualityMethod*> methods;
  for (const std::string& name : names) {
    auto m = FindQualityMethod(name);
    if (!m.ok()) return m.error();
    methods.push_back(*m);
  }
  return methods;
}

}  // namespace reenact::eval
