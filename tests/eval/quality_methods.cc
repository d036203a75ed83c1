#include "tests/eval/quality_methods.h"

namespace reenact::eval {

const std::vector<QualityMethod>& QualityMethods() {
  static const std::vector<QualityMethod> methods = {
      {"thesis",
       "the thesis exactly: whole-skeleton Eq. 5 selects one stored frame per output frame, "
       "Eq. 6-16 map every cylinder onto it, no occlusion handling",
       [](const viewer::Reenactment& clip, int k, const PinholeCamera& camera,
          const Eigen::Isometry3d& viewer_from_world,
          const std::function<int(int)>& texture_for_frame) {
         viewer::ReenactedFrame frame = clip.Build(k, camera, viewer_from_world, texture_for_frame);
         frame.draw.bones.clear();
         frame.draw.floor.reset();
         frame.draw.background = nullptr;
         return frame;
       }},
      {"steady",
       "thesis + steady motion: the posed skeleton from the clip's steady track (skeletons the "
       "capture flagged interpolated across from their neighbours, every joint One Euro "
       "filtered: min cutoff 1 Hz, beta 8 Hz per m/s, derivative cutoff 1 Hz, "
       "forward and backward; common/filter/steady_motion.h); selection and mapping as the thesis",
       [](const viewer::Reenactment& clip, int k, const PinholeCamera& camera,
          const Eigen::Isometry3d& viewer_from_world,
          const std::function<int(int)>& texture_for_frame) {
         viewer::ReenactedFrame frame = clip.BuildPosed(k, clip.SteadySkeletonInWorld(k), camera,
                                                        viewer_from_world, texture_for_frame);
         frame.draw.bones.clear();
         frame.draw.floor.reset();
         frame.draw.background = nullptr;
         return frame;
       }},
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

}  // namespace reenact::eval
