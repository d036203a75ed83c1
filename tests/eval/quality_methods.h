#pragma once
// The reenactment methods `reenact-eval quality` compares, by name. Each turns output frame k
// of a clip and a viewer camera into the renderer's draw list (cylinders only: no floor, no
// skeleton overlay), with the body part of every cylinder for provenance. A new method is one
// more entry in QualityMethods(); every method runs on the same captured clip, cameras and
// ground truth in one run, so rows compare directly.

#include <Eigen/Geometry>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "common/error/expected.h"
#include "common/geometry/pinhole_camera.h"
#include "viewer-client/play/reenactment.h"

namespace reenact::eval {

struct QualityMethod {
  using Build = std::function<viewer::ReenactedFrame(
      const viewer::Reenactment& clip, int k, const PinholeCamera& viewer_camera,
      const Eigen::Isometry3d& viewer_from_world, const std::function<int(int)>& texture_for_frame,
      PartSelectionHistory* history)>;

  std::string name;     // command-line name, e.g. "thesis"
  std::string summary;  // one line for the docs
  // texture_for_frame maps a stored frame to the renderer's texture index (uploads on demand);
  // history (may be null) carries per-part selection from one output frame to the next of the
  // same viewpoint, for hysteresis.
  Build build;
  // The body shape the method draws (its TexturingOptions::shape): its stored textures carry
  // part-label maps of that shape.
  viewer::BodyShape shape = viewer::BodyShape::kCylinders;
  // The method poses from the steady track and is given the clip with steady_motion on (its
  // stored frames on the steady track too; reenactment.h).
  bool steady = false;
};

// Every method, in the order tables list them.
const std::vector<QualityMethod>& QualityMethods();

// The method of that name; error "usage" naming the known methods otherwise.
Expected<const QualityMethod*> FindQualityMethod(std::string_view name);

// The methods of those names, in order; the first unknown name's error otherwise.
Expected<std::vector<const QualityMethod*>> FindQualityMethods(const std::vector<std::string>& names);

}  // namespace reenact::eval
