#pragma once
// Steady motion for a recorded skeleton track (issue 9): skeletons the capture flagged (the
// bone-length check, manifest.flagged_skeleton_frames) are dropped and replaced by linear
// interpolation in time between their nearest unflagged neighbours, then every joint's
// trajectory is smoothed by a One Euro filter (one_euro_filter.h) forward in time.
//
// Units: joint positions in metres in any one frame shared by the whole track (the world
// frame of a clip), times in seconds; the filter's speed is in m/s, so beta is in Hz per m/s.
//
// Interpolation of flagged frame n between unflagged neighbours p < n < q, per joint:
//   present in both: s = s_p + w (s_q - s_p), w = (t_n - t_p) / (t_q - t_p) (by frame index
//     when t_q <= t_p), confidence min(c_p, c_q);
//   present in one: that one's position and confidence (held);
//   present in neither: missing.
// Before the first or after the last unflagged frame the nearest unflagged skeleton is held.
// With no unflagged frame at all nothing can be interpolated: the track is returned as given.
//
// Filtering: a joint missing (confidence 0) at a frame stays missing and restarts its filter,
// so the next present sample passes unchanged; confidences are kept. A recorded clip is known
// whole, so by default (zero_phase) the filter runs forward and then backward in time over the
// forward result: the backward pass leads by what the forward pass lags, so a ramp at speed v
// comes out without the forward filter's lag v tau (tau = 1 / (2 pi cutoff)) and the
// smoothing of noise is that of the two passes together. zero_phase off: forward only (causal,
// as for a live stream).

#include <span>
#include <vector>

#include "common/filter/one_euro_filter.h"
#include "common/skeleton/skeleton.h"

namespace reenact {

struct SteadyMotionOptions {
  bool interpolate_flagged = true;  // replace flagged skeletons by interpolation
  bool filter = true;               // One Euro filter every joint
  bool zero_phase = true;           // forward then backward pass (see above)
  // Defaults for a body at 30 fps, chosen on `reenact-eval quality` (docs/quality.md): at
  // rest a 1 Hz cutoff (tau = 0.16 s) removes tracker jitter; a limb moving at 1 m/s raises
  // it to 1 + 8 * 1 = 9 Hz (tau = 18 ms), so a kick is followed closely.
  OneEuroOptions one_euro{.min_cutoff_hz = 1.0, .beta = 8.0, .derivative_cutoff_hz = 1.0};

  void Check() const { one_euro.Check(); }
};

// Flagged skeletons replaced as above. Precondition (CHECK): the three spans have one size,
// times finite.
std::vector<Skeleton> InterpolateFlaggedSkeletons(std::span<const Skeleton> skeletons,
                                                  std::span<const double> times_s,
                                                  std::span<const bool> flagged);

// Interpolation (if enabled), then filtering (if enabled). Same preconditions.
std::vector<Skeleton> SteadySkeletonTrack(std::span<const Skeleton> skeletons,
                                          std::span<const double> times_s,
                                          std::span<const bool> flagged,
                                          const SteadyMotionOptions& options);

}  // namespace reenact
