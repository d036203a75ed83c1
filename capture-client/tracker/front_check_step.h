#pragma once
// Front from the fit, while it is uncertain: for `frames` tracked frames after a start from
// the silhouette (its heading a guess), every `every`-th frame the body is also fitted turned
// around on the same data (limb_swap.h's TurnedAround), and that fit, when good and cheaper
// than (1 - gain) times the frame's, becomes a rival track. The start chose its heading
// standing still, where front and back fit nearly alike; once the subject moves, the knees and
// elbows, which bend one way only, tell them apart. Later the track's own continuity is the
// better guide: checked throughout, a turn made in a fast spin was taken the wrong way round.
//
// The rival is followed for at most confirm_frames frames, each frame fitted from its own last
// pose as the track is (StepFrame::fit_as_track), the costs of both summed over the frames
// followed. It replaces the track as soon as its sum is at most (1 - gain) times the track's,
// is dropped as soon as the track's is at most (1 - gain) times the rival's, or when its fit is
// not good, and replaces the track when neither has happened after confirm_frames frames (one
// frame's cost tells front from back poorly where the body shows few points). A rival that
// would turn a body facing the sensor away from it needs (1 - turn_away_gain) instead and is
// never taken undecided: a person in front of a sensor faces it unless the data say otherwise
// clearly, and on real depth (utd-mhad, Kinect v1 at 3 m) the wrong way round was the cheaper
// fit on a third of the sequences. confirm_frames 0: the turned fit is judged on its own frame.

#include <optional>

#include "capture-client/tracker/correction_step.h"

namespace reenact::capture {

struct FrontCheckOptions {
  int frames = 30;         // >= 1
  int every = 5;           // >= 1
  double gain = 0.1;       // [0, 1)
  // The gain a rival needs to turn a body that faces the sensor away from it, [gain, 1).
  double turn_away_gain = 0.5;
  int confirm_frames = 5;  // >= 0

  void Check() const;
};

class FrontCheckStep final : public CorrectionStep {
 public:
  explicit FrontCheckStep(const FrontCheckOptions& options);
  std::string_view name() const override { return "front-check"; }
  AcceptanceRule rule() const override;
  std::vector<Candidate> Propose(const StepFrame& frame, const BodyFitResult& current) override;
  void OnTrackStart(TrackStart start) override;
  void Reset() override;

 private:
  std::vector<Candidate> FollowRival(const StepFrame& frame, const BodyFitResult& current);

  struct Rival {
    ArticulatedPose pose;
    double rival_cost = 0;  // summed over the frames followed after the check's
    double track_cost = 0;  // the track's over the same frames
    int frames = 0;         // followed so far
  };
  FrontCheckOptions options_;
  int frames_since_start_ = -1;  // tracked frames since a start from the silhouette; -1: none
  std::optional<Rival> rival_;
};

}  // namespace reenact::capture
