#pragma once
// Experiments on the depth tracker (capture-client/tracker/): its method without a step or a
// part of one (an ablation), and the model's floor, an oracle fit from the ground truth.
//
// Ablations (reenact-eval tracker --without NAME[,NAME...]):
//   turned-starts   the turned starts (turned_starts_step.h)
//   limb-jump       the turned starts' refusal of a fit where a limb jumped from its data
//   uncross-arms    uncrossing the arms; uncross-legs: the legs (uncross_step.h)
//   uncross-return  the returned arm as a start when uncrossing (the swap alone)
//   front-check     the front check after a start from the silhouette (front_check_step.h)
//   front-confirm   the front check's rival followed before it is taken (taken at once)
//   travel-heading  the front from the walking direction (travel_heading_step.h)
//   limb-search     the limb search after each fit (body_fitter.h)
//   held-twists     the limb search's hypotheses with the upper segment held
//   static-scene    the static scene learned beside the person (static_scene_voxels.h)
//   trunk-breadth   the calibration's measured trunk breadth (average proportions instead)
//   torso-depth     the trunk's depth measured from side views (body_measurement.h)

#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "capture-client/tracker/skeleton_tracker.h"
#include "capture-client/tracker/tracker_method.h"
#include "common/skeleton/skeleton.h"

namespace reenact::eval {

const std::vector<std::string_view>& TrackerAblations();

// The product's method (DefaultTrackerMethod) less the ablations named in `without` (each one
// of TrackerAblations(): CHECK); its steps built here in the product's order, so that an empty
// `without` gives the product's method.
capture::TrackerMethod ExperimentMethod(const capture::SkeletonTrackerOptions& options,
                                        const std::set<std::string>& without);

// The model's floor on the tracker's last frame: what this body model reaches from a start it
// could not know, such as the ground truth's skeleton. `posed`: the tracker's current body
// posed as near start_in_sensor as its shape allows (ArticulatedBody::PoseFromSkeleton: root
// from the pelvis and torso joints, limbs by their bone directions); `fitted`: that pose fitted
// to the last frame's observation as a tracked frame's own start is (FitBody with the method's
// fit options and limits; no steps). nullopt unless the last frame was tracked or recovered
// (SkeletonTracker::last_fit). fitted_cost and track_cost: CostWithLostPoints (body_fit.h) of
// that fit and of the fit the track kept, on the same observation: a fit from the truth that
// costs less is a better minimum the track missed (the search's loss); one that costs as much
// or more says the data prefer the track's pose (the model's).
struct OracleFit {
  Skeleton posed, fitted;  // sensor frame
  double fitted_cost = 0, track_cost = 0;
};
std::optional<OracleFit> FitLastFrameFrom(const capture::SkeletonTracker& tracker,
                                          const Skeleton& start_in_sensor);

}  // namespace reenact::eval
