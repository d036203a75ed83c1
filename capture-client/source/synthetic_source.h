#pragma once
// FrameSource over the synthetic scene: renders each frame from the scene's sensor and passes
// its ground truth (sensor pose, skeleton, person mask) along.

#include <memory>
#include <string_view>

#include "capture-client/source/frame_source.h"
#include "synthetic/synthetic_scene.h"

namespace reenact::capture {

class SyntheticSource : public FrameSource {
 public:
  static Expected<std::unique_ptr<FrameSource>> Open(std::string_view scenario, uint64_t seed = 1,
                                                     const SyntheticBodySpec& body = {});
  // From the argument of a "synthetic:" source spec (source_argument.h):
  //   SCENARIO[?body=FILE.glb[&body_height=M]]
  // e.g. "turn-and-kick" (the procedural body), "turn-and-kick?body=CesiumMan.glb",
  // "bvh:walk.bvh?body=CesiumMan.glb&body_height=1.7"; body=procedural names the default.
  // Errors: "usage" for an empty scenario or a bad option; those of Open.
  static Expected<std::unique_ptr<FrameSource>> OpenSpec(std::string_view argument);

  const SensorInfo& info() const override { return info_; }
  Expected<std::optional<SensorFrame>> Next() override;

 private:
  SyntheticSource(SyntheticScene scene, SensorInfo info);
  SyntheticScene scene_;
  SensorInfo info_;
  int next_ = 0;
};

}  // namespace reenact::capture
