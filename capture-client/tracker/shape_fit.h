#pragma once
// Fitting the body's segment lengths together with its pose to the calibration pose's depth
// (for bodies far from average proportions). Used by CalibrateBody after the pose-only
// fit; bone lengths are fixed afterwards.
//
// Unknowns: the pose (ArticulatedBody's 31 step parameters) and the 11 lengths of
// ShapeLength (metres). Levenberg-Marquardt on the residual vector (Jacobian by central
// differences: lengths by 1 mm, pose parameters by 1e-4 m or rad through ArticulatedBody::Step):
//  - data: for each point, sign(e) sqrt(2 Huber(e)) with e its signed distance to the nearest
//    capsule's surface (body_fit.h); 0 beyond outlier_m;
//  - silhouette / free space: sqrt(w) e on every capsule's axis samples (body_fit.h's term,
//    its weight w);
//  - height: sqrt(height_weight N) (StandingHeight(shape) - height_m): the measured standing
//    height holds the sum of the vertical lengths (N = data points);
//  - priors: sqrt(prior_weight N) (L_k - prior_k) / prior_k * prior_scale_m for each length,
//    pulling towards the proportional shape: a length the depth does not show (the knee
//    along a straight leg) stays near its prior. A relative change x of a length costs as
//    much as prior_weight of the data points each x * prior_scale_m off the surface. Lengths
//    are kept within [min_ratio, max_ratio] of their prior.
// Capsule radii are held (re-estimate them after, as CalibrateBody does).

#include <array>
#include <vector>

#include "capture-client/tracker/articulated_body.h"
#include "capture-client/tracker/body_fit.h"

namespace reenact::capture {

enum class ShapeLength : int {
  kHipHalfWidth = 0,
  kHipDrop,
  kLowerSpine,
  kUpperSpine,
  kShoulderHalfWidth,
  kShoulderDrop,
  kUpperArm,
  kForearm,
  kThigh,
  kShin,
  kHeadRise,
};
inline constexpr int kShapeLengthCount = 11;

double GetLength(const BodyShape& shape, ShapeLength k);
void SetLength(BodyShape* shape, ShapeLength k, double value);

struct ShapeFitOptions {
  int iterations = 12;          // LM iterations, >= 1
  double height_weight = 1.0;   // >= 0
  double prior_weight = 0.002;  // >= 0
  double prior_scale_m = 0.1;   // > 0
  double min_ratio = 0.5;       // 0 < min_ratio <= 1 <= max_ratio
  double max_ratio = 2.0;
  double initial_lambda = 1e-2;  // > 0
  // Which lengths are fitted (index: ShapeLength); the others stay at the prior. The arm
  // chain (shoulder width, upper arm, forearm) is held: the forearm's capsule ends at the
  // palm centre, so the unmodelled fingers pull the arm's reach long (5 cm on the procedural
  // subject, whichever of the three takes it); CalibrateBody sets it from the arm span, which
  // accounts for the fingers.
  std::array<bool, kShapeLengthCount> free = {true,  true,  true, true, false, true,
                                              false, false, true, true, true};

  void Check() const;
};

struct ShapeFitResult {
  BodyShape shape;
  ArticulatedPose pose;
  double initial_cost = 0, cost = 0;  // 0.5 |r|^2 at the start and the end
  int iterations = 0;
};

// Fits from (prior, start). height_m > 0: the measured standing height. An observation without
// points returns the start unchanged.
ShapeFitResult FitBodyShape(const BodyShape& prior, const ArticulatedPose& start,
                            const BodyObservation& observation, double height_m,
                            const BodyFitOptions& fit_options, const ShapeFitOptions& options,
                            const JointLimits& limits = {});

// The same fit over several frames of one subject (on-the-fly calibration, without the
// calibration pose): one set of lengths, one pose per frame (starts[f] for observations[f],
// not null). The data and silhouette terms sum over the frames; the height and prior terms
// count once, with N the data points of all frames, so that their weight against the data
// is the one-frame fit's. Frames with varied poses (legs apart in a walk) show the lengths
// that one straight-legged frame hides (the hips' height). Without frames or points, the
// prior and the starts are returned.
struct MultiFrameShapeFit {
  BodyShape shape;
  std::vector<ArticulatedPose> poses;
  double initial_cost = 0, cost = 0;
  int iterations = 0;
};
MultiFrameShapeFit FitBodyShapeFrames(const BodyShape& prior,
                                      const std::vector<ArticulatedPose>& starts,
                                      const std::vector<const BodyObservation*>& observations,
                                      double height_m, const BodyFitOptions& fit_options,
                                      const ShapeFitOptions& options,
                                      const JointLimits& limits = {});

}  // namespace reenact::capture
