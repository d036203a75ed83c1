#pragma once
// The gap ratio of the tracker's prediction in time (SkeletonTrackerOptions::max_gap_ratio,
// skeleton_tracker_options.h): how many of the last frame intervals lie between the last tracked
// pose and this frame.
//
//   g = (t - t1) / (t1 - t0)
//
// t this frame's time, t1 and t0 the times of the last two tracked poses (seconds). A live
// sensor drops frames unevenly (a full queue, colour and depth parting), and a frame without a
// person leaves a gap too, so the last root displacement is carried on g times.

#include <optional>

namespace reenact::capture {

// g above, clamped to at most max_ratio (>= 1: CHECK); 1 (evenly spaced frames) when a time is
// unknown or not finite, when the times are not in order t0 < t1 < t, or when g lies within
// 1e-6 of 1 (equal intervals up to rounding, so that evenly timed frames predict exactly as
// untimed ones).
double GapRatio(std::optional<double> t, std::optional<double> t1, std::optional<double> t0,
                double max_ratio);

}  // namespace reenact::capture
