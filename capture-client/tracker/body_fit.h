#pragma once
// Fitting the articulated body (articulated_body.h) to one depth frame's person points:
// Levenberg-Marquardt over the root pose and the joint rotations, bone lengths fixed, joint
// limits enforced after every step (ArticulatedBody::Clamp), starting from a given pose.
//
// Cost (all residuals in metres):
//  - Data: for each person point p (subsampled), its signed distance to the surface of the
//    nearest capsule, e = |p - c| - radius (c the nearest point on the capsule's axis),
//    Huber-weighted with scale huber_m; points farther than outlier_m from every capsule are
//    left out (another object, a hand the model lost).
//  - Silhouette and free space, on samples_per_capsule points q along every capsule's axis
//    (so occluded parts cannot drift into the torso or off the person): where q projects
//    outside the person's silhouette, e = the image distance to the silhouette converted to
//    metres at q's depth (distance transform of the mask); where it projects onto a reading
//    z_obs in front of which q lies (q.z < z_obs), e = z_obs - q.z (the axis must lie behind
//    the visible surface). Weighted so that these terms together weigh
//    silhouette_weight times the data term. Nothing where q projects outside the image.
//  - Damping: Levenberg-Marquardt's lambda times diag(H) plus damping times the data term's
//    size on every parameter (a weak pull to the start pose for unobserved joints).
// Jacobians are analytic: a rotation omega at joint j moves a point x it carries by
// omega x (x - j) (see articulated_body.h). A residual on segment s depends only on the root's
// translation and the joints of s's chain to the root (at most 16 of the 31 parameters), so
// the normal equations are summed per segment over those and scattered. Each point's nearest
// capsule is searched from the one of the last iteration, passing capsules whose bounding
// sphere lies farther than the best so far (the same capsule as a full search).

#include <Eigen/Core>
#include <array>
#include <vector>

#include "capture-client/tracker/articulated_body.h"
#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"

namespace reenact::capture {

struct BodyFitOptions {
  int iterations = 8;              // LM iterations (each re-finds the nearest capsules), >= 1
  double huber_m = 0.02;           // Huber scale of the data residuals, > 0
  double outlier_m = 0.15;         // data points farther from every capsule are ignored, > 0
  double inlier_m = 0.03;          // |e| at most this counts as support (confidence), > 0
  int samples_per_capsule = 5;     // axis samples of the silhouette/free-space term, >= 0
  double silhouette_weight = 0.3;  // weight of that term relative to the data term, >= 0
  double damping = 1e-3;           // damping per data point on every parameter, >= 0
  double initial_lambda = 1e-3;    // LM's lambda at the start, > 0

  void Check() const;
};

// One frame's observation of the person: its points and its silhouette on a grid of every
// grid_step_px-th pixel of `camera`.
struct BodyObservation {
  PinholeCamera camera;
  int grid_step_px = 1;
  ImageGray8 silhouette;    // grid-sized, 255 = person
  Image<float> depth_m;     // grid-sized readings, metres, 0 = hole
  Image<float> outside_px;  // grid-sized distance (grid pixels) to the silhouette; 0 in it
  std::vector<Eigen::Vector3d> points;  // sensor frame, the fit's data (subsampled)
  int point_spacing_px = 1;             // image pixels between neighbouring data points
};

// Builds the observation: the distance transform of the silhouette (exact Euclidean) and the
// data points, every `subsample`-th grid point of the person in x and y (>= 1).
BodyObservation MakeObservation(const PinholeCamera& camera, int grid_step_px,
                                const ImageGray8& silhouette, const Image<float>& depth_m,
                                const std::vector<Eigen::Vector3d>& points,
                                const std::vector<Eigen::Vector2i>& pixels, int subsample);

// Drops the observation's data points farther than max_m from the surface of the body posed
// as `posed` (another object merged into the person's region); returns how many were
// dropped.
int KeepPointsNearBody(const ArticulatedBody& body, const PosedBody3& posed, double max_m,
                       BodyObservation* observation);

struct BodyFitResult {
  ArticulatedPose pose;
  PosedBody3 posed;
  double cost = 0;              // final cost (data + silhouette terms)
  int iterations = 0;           // LM iterations run
  int points = 0;               // data points
  double inlier_share = 0;      // points with |e| <= inlier_m
  double outlier_share = 0;     // points beyond outlier_m of every capsule (unexplained)
  double rms_m = 0;             // RMS of e over the points within outlier_m
  double silhouette_rms_m = 0;  // RMS of the silhouette/free-space residuals over the samples
  // Inlier points per segment (SegmentSupport::support below), and the visible area the
  // segment's capsules would cover (projected silhouette, grid pixels at the data's
  // subsampling) for comparison: a part beyond the image's edge, like one hidden by the body,
  // has little support for its area.
  std::array<int, kBodySegmentCount> support{};
  std::array<double, kBodySegmentCount> expected_support{};
  // Sum of support over the part of the model's silhouette within the image: the share of
  // what the model would show in the image that the data covers (below 1 where the body hides
  // its own parts; a part beyond the image's edge is not seen, not missing).
  double coverage = 0;
  // Mean of the points within inlier_m (the start pose's root when there are none).
  Eigen::Vector3d inlier_centroid = Eigen::Vector3d::Zero();
};

// The data points each segment explains at a pose. support: the points whose nearest capsule
// (the smallest e, the first of equals) is one of the segment's, with |e| <= inlier_m.
// exclusive: of those, the points that no capsule of another segment lies within inlier_m of
// as well, the limb's other segment excepted (upper arm and forearm, thigh and shin meet at
// the elbow and knee); for the trunk's segments (pelvis, lower spine, chest, head) every
// supporting point counts. A limb lying on the trunk or on another limb takes their points as
// support, but not exclusively: the data do not tell it from the part it lies on.
struct SegmentSupport {
  std::array<int, kBodySegmentCount> support{};
  std::array<int, kBodySegmentCount> exclusive{};
};
SegmentSupport SupportAt(const ArticulatedBody& body, const PosedBody3& posed,
                         const BodyObservation& observation, double inlier_m);

// For each point, the segment of its nearest capsule at a pose (the smallest signed surface
// distance e, the first of equals; as SupportAt), or -1 where |e| > max_m.
std::vector<int> NearestSegments(const ArticulatedBody& body, const PosedBody3& posed,
                                 const std::vector<Eigen::Vector3d>& points, double max_m);

// The silhouette/free-space residual (see above) at an axis point q (sensor frame) and its
// gradient with respect to q; false when q projects outside the image (or lies behind the
// sensor) or lies inside the silhouette behind the observed surface (no term).
bool SilhouetteResidual(const BodyObservation& observation, const Eigen::Vector3d& q, double* e,
                        Eigen::Vector3d* gradient);

// The weight of one silhouette sample relative to one data point (see above).
double SilhouetteSampleWeight(const BodyObservation& observation, const BodyFitOptions& options,
                              int capsule_count);

// Huber cost of a data residual with scale delta.
inline double HuberCost(double e, double delta) {
  const double a = e < 0 ? -e : e;
  return a <= delta ? 0.5 * e * e : delta * (a - 0.5 * delta);
}

// A fit's cost with each point it leaves beyond outlier_m counted at outlier_m's cost: such
// points cost nothing in the fit, so a fit could cost less by losing a limb's points.
double CostWithLostPoints(const BodyFitResult& fit, const BodyFitOptions& options);

// Fits from `start`. An observation without points returns the start pose with zero support
// (no step is taken).
BodyFitResult FitBody(const ArticulatedBody& body, const ArticulatedPose& start,
                      const BodyObservation& observation, const BodyFitOptions& options,
                      const JointLimits& limits = {});

}  // namespace reenact::capture
