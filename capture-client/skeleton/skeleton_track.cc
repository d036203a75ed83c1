#include "capture-client/skeleton/skeleton_track.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

namespace reenact::capture {
namespace {

std::string Number(double v) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), v);
  return std::string(buffer, result.ptr);
}

Error Corrupt(const std::string& description, size_t frame, const std::string& what) {
  return MakeError("corrupt", "skeleton track " + description + ": frame " + std::to_string(frame) +
                                  ": " + what);
}

}  // namespace

void SkeletonTrackLookupOptions::Check() const {
  REENACT_CHECK(std::isfinite(timestamp_tolerance_s) && timestamp_tolerance_s >= 0,
                "timestamp_tolerance_s must be finite and >= 0");
  REENACT_CHECK(std::isfinite(timestamp_offset_s), "timestamp_offset_s must be finite");
}

Expected<SkeletonTrack> SkeletonTrack::Create(std::vector<SkeletonTrackFrame> frames,
                                              std::string description,
                                              const SkeletonTrackLookupOptions& options) {
  options.Check();
  if (frames.empty())
    return MakeError("corrupt", "skeleton track " + description +
                                    " has no frames; give a file with at least one skeleton");
  const bool timed = frames.front().timestamp_s.has_value();
  for (size_t i = 0; i < frames.size(); ++i) {
    const SkeletonTrackFrame& f = frames[i];
    if (f.timestamp_s.has_value() != timed)
      return Corrupt(description, i,
                     timed ? "has no timestamp_s while frame 0 has one; give every frame a "
                             "timestamp or none"
                           : "has a timestamp_s while frame 0 has none; give every frame a "
                             "timestamp or none");
    if (!timed && !f.frame_index)
      return Corrupt(description, i,
                     "has neither timestamp_s nor frame_index; a frame needs at least one");
    if (f.timestamp_s && !std::isfinite(*f.timestamp_s))
      return Corrupt(description, i, "timestamp_s is not a finite number");
    if (f.frame_index && *f.frame_index < 0)
      return Corrupt(description, i,
                     "frame_index " + std::to_string(*f.frame_index) + " is negative");
    if (i > 0 && f.timestamp_s && *f.timestamp_s <= *frames[i - 1].timestamp_s)
      return Corrupt(description, i,
                     "timestamp_s " + Number(*f.timestamp_s) + " is not after the previous " +
                         "frame's " + Number(*frames[i - 1].timestamp_s) +
                         "; timestamps must increase strictly");
    if (f.frame_index) {
      for (size_t k = i; k-- > 0;) {
        if (!frames[k].frame_index) continue;
        if (*f.frame_index <= *frames[k].frame_index)
          return Corrupt(description, i,
                         "frame_index " + std::to_string(*f.frame_index) + " is not after frame " +
                             std::to_string(k) + "'s " + std::to_string(*frames[k].frame_index) +
                             "; frame indices must increase strictly");
        break;
      }
    }
    for (int j = 0; j < kJointCount; ++j) {
      const std::string joint(JointName(static_cast<Joint>(j)));
      const double c = f.skeleton_in_sensor.confidence[j];
      if (!(c >= 0 && c <= 1))
        return Corrupt(description, i,
                       "joint " + joint + ": confidence " + Number(c) + " is outside [0, 1]");
      if (!f.skeleton_in_sensor.position[j].allFinite())
        return Corrupt(description, i, "joint " + joint + ": position is not finite");
    }
  }
  SkeletonTrack track;
  track.frames_ = std::move(frames);
  track.description_ = std::move(description);
  track.options_ = options;
  track.keyed_by_timestamp_ = timed;
  return track;
}

void SkeletonTrack::set_lookup_options(const SkeletonTrackLookupOptions& options) {
  options.Check();
  options_ = options;
}

std::optional<Skeleton> SkeletonTrack::ForFrame(int64_t index, double timestamp_s) const {
  if (keyed_by_timestamp_) {
    const double t = timestamp_s + options_.timestamp_offset_s;
    if (!std::isfinite(t)) return std::nullopt;
    const auto after = std::lower_bound(
        frames_.begin(), frames_.end(), t,
        [](const SkeletonTrackFrame& f, double value) { return *f.timestamp_s < value; });
    const SkeletonTrackFrame* best = nullptr;
    double best_dt = std::numeric_limits<double>::infinity();
    if (after != frames_.begin()) {
      best = &*std::prev(after);
      best_dt = t - *best->timestamp_s;
    }
    if (after != frames_.end() && *after->timestamp_s - t < best_dt) {
      best = &*after;
      best_dt = *after->timestamp_s - t;
    }
    if (best == nullptr || !(best_dt <= options_.timestamp_tolerance_s)) return std::nullopt;
    return best->skeleton_in_sensor;
  }
  int64_t key = 0;
  if (__builtin_add_overflow(index, options_.frame_index_offset, &key)) return std::nullopt;
  const auto it = std::lower_bound(
      frames_.begin(), frames_.end(), key,
      [](const SkeletonTrackFrame& f, int64_t value) { return *f.frame_index < value; });
  if (it == frames_.end() || *it->frame_index != key) return std::nullopt;
  return it->skeleton_in_sensor;
}

}  // namespace reenact::capture
