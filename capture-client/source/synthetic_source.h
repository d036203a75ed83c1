#pragma once
// FrameSource over the synthetic scene: renders each frame from the scene's sensor and passes
// its ground truth (sensor pose, skeleton, person mask) along.

#include <memory>
#include <string_view>

#include "capture-client/source/frame_source.h"
#include "capture-client/synthetic/synthetic_scene.h"

namespace reenact::capture {

class SyntheticSource : public FrameSource {
 public:
  static Expected<std::unique_ptr<FrameSource>> Open(std::string_view scenario, uint64_t seed = 1);

  const SensorInfo& info() const override { return info_; }
  Expected<std::optional<SensorFrame>> Next() override;

 private:
  SyntheticSource(SyntheticScene scene, SensorInfo info);
  SyntheticScene scene_;
  SensorInfo info_;
  int next_ = 0;
};

}  // namespace reenact::capture
