#pragma once
// A frame source seen as a real sensor delivers it: no sensor pose and no person mask, and
// optionally no skeleton and no depth. Keeps what it removed (the source's pose and its
// skeleton moved into the sensor frame) so that tests can compare against it and stand in
// for an imported skeleton track.

#include <algorithm>
#include <memory>
#include <optional>
#include <vector>

#include "capture-client/source/frame_source.h"

namespace reenact::test_support {

class AsRealSensor : public capture::FrameSource {
 public:
  struct Removed {
    double timestamp_s = 0;
    std::optional<Eigen::Isometry3d> world_from_sensor;
    std::optional<Skeleton> skeleton_in_sensor;
  };

  AsRealSensor(std::unique_ptr<capture::FrameSource> inner, bool keep_skeleton,
               bool zero_depth = false)
      : inner_(std::move(inner)), keep_skeleton_(keep_skeleton), zero_depth_(zero_depth) {}

  const capture::SensorInfo& info() const override { return inner_->info(); }

  Expected<std::optional<capture::SensorFrame>> Next() override {
    auto next = inner_->Next();
    if (!next.ok() || !next->has_value()) return next;
    capture::SensorFrame& f = **next;
    Removed r{f.timestamp_s, f.world_from_sensor, std::nullopt};
    if (f.skeleton_in_world && f.world_from_sensor)
      r.skeleton_in_sensor = f.skeleton_in_world->Transformed(f.world_from_sensor->inverse());
    removed_.push_back(r);
    f.world_from_sensor.reset();
    f.person_mask.reset();
    if (!keep_skeleton_) f.skeleton_in_world.reset();
    if (zero_depth_) std::fill(f.depth.data.begin(), f.depth.data.end(), 0);
    return next;
  }

  const std::vector<Removed>& removed() const { return removed_; }

  // The removed skeletons as an imported track would give them (RecordOptions::skeletons).
  std::optional<Skeleton> SkeletonOf(int64_t index) const {
    return index >= 0 && index < static_cast<int64_t>(removed_.size())
               ? removed_[index].skeleton_in_sensor
               : std::nullopt;
  }

 private:
  std::unique_ptr<capture::FrameSource> inner_;
  bool keep_skeleton_, zero_depth_;
  std::vector<Removed> removed_;
};

}  // namespace reenact::test_support
