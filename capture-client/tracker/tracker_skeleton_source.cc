#include "capture-client/tracker/tracker_skeleton_source.h"

#include <iomanip>
#include <sstream>

namespace reenact::capture {

std::string TrackerSourceStats::Describe() const {
  std::ostringstream s;
  if (calibration_frame < 0) {
    s << "tracker: no skeleton in " << frames << " frames: ";
    const int people = detect[static_cast<int>(DetectStatus::kOk)];
    if (people == 0) {
      s << "no person found (no depth: " << detect[static_cast<int>(DetectStatus::kNoDepth)]
        << ", nothing person-sized: " << detect[static_cast<int>(DetectStatus::kNoPerson)]
        << " frames); the subject must be 0.4-6 m from the sensor, its head and shoulders in "
           "view, apart from walls and furniture by a step in depth";
    } else {
      s << "a person in " << people
        << " frames, but never in the calibration pose (facing the sensor, arms held out to "
           "the sides) nor trackable with average proportions";
    }
    return s.str();
  }
  s << "tracker: " << tracked << " of " << frames << " frames tracked; started at frame "
    << calibration_frame
    << (from_calibration_pose ? " from the calibration pose"
                              : " without the calibration pose: average proportions");
  if (!from_calibration_pose)
    s << ", the head " << std::fixed << std::setprecision(2) << head_scale << " and the legs "
      << leg_scale << " times the average's as measured from the silhouette";
  s << "; " << losses << " losses, " << recoveries << " recoveries; the sensor's pose on " << posed
    << " of " << frames << " frames";
  if (posed < frames) s << " (the static scene beside the subject is left in on the others)";
  return s.str();
}

TrackerSkeletonSource::TrackerSkeletonSource(const SensorInfo& info,
                                             const SkeletonTrackerOptions& options)
    : info_(info),
      tracker_(std::make_unique<SkeletonTracker>(info.depth_camera, info.depth_scale_m, options)) {}

FrameSkeletonSource TrackerSkeletonSource::Function() {
  return [this](int64_t index, const SensorFrame& frame, const FramePoseHint& pose) {
    return Track(index, frame, pose);
  };
}

Expected<std::optional<Skeleton>> TrackerSkeletonSource::Track(int64_t index,
                                                               const SensorFrame& frame,
                                                               const FramePoseHint& pose) {
  const PinholeCamera& cam = info_.depth_camera;
  if (frame.depth.width != cam.width || frame.depth.height != cam.height ||
      frame.depth.channels != 1)
    return MakeError("corrupt", "frame " + std::to_string(index) + ": depth image is " +
                                    std::to_string(frame.depth.width) + "x" +
                                    std::to_string(frame.depth.height) +
                                    ", the depth camera's is " + std::to_string(cam.width) + "x" +
                                    std::to_string(cam.height));
  const TrackState before = tracker_->state();
  const TrackFrameResult r = tracker_->Track(
      frame.depth, pose.world_from_sensor,
      pose.world_from_sensor ? pose.world_up : std::optional<Eigen::Vector3d>(), frame.timestamp_s);
  ++stats_.frames;
  stats_.posed += pose.world_from_sensor.has_value();
  ++stats_.detect[static_cast<int>(r.detect)];
  if (r.calibrated && stats_.calibration_frame < 0) {
    stats_.calibration_frame = static_cast<int>(index);
    stats_.from_calibration_pose =
        tracker_->calibration() && tracker_->calibration()->from_calibration_pose;
  }
  const auto& calibration = tracker_->calibration();
  if (calibration && !calibration->from_calibration_pose) {
    const BodyShape average = BodyShape::FromHeight(calibration->height_m);
    stats_.head_scale = calibration->shape.head_radius / average.head_radius;
    stats_.leg_scale =
        (calibration->shape.thigh + calibration->shape.shin) / (average.thigh + average.shin);
  }
  if (r.recovered) ++stats_.recoveries;
  if (before == TrackState::kTracking && r.state == TrackState::kLost) ++stats_.losses;
  if (r.skeleton) ++stats_.tracked;
  return r.skeleton;
}

}  // namespace reenact::capture
