#pragma once
// The trunk's depth (front to back) measured from side views while tracking, and its breadth
// from the calibration pose (MeasureTrunkBreadth below). The calibration pose faces the
// sensor: it shows the trunk's breadth, but its depth only through the curvature of the front
// surface, and the calibrated trunk comes out 0.53-0.56 times as deep as broad on both
// synthetic bodies, against 0.65-0.7 (procedural) and 0.76 (CesiumMan) on their meshes. A trunk
// too shallow for a side view can only cover the silhouette by turning its breadth towards the
// sensor: its heading is then 20-30 degrees off, and a hidden arm, with no points of its own to
// hold it, follows it.
//
// Model. The trunk's cross-section is a stadium: two capsules of radius r whose axes lie s to
// either side of the spine (BodyShape::torso_radius, torso_half_spread), breadth 2 (r + s),
// depth 2 r. Seen along a horizontal direction at angle theta from the trunk's left axis
// (theta = 0: side-on), its silhouette is 2 w wide across the line of sight, with
//   w = r + s |sin theta|,
// so a side view shows the half depth r directly.
//
// Method, per tracked frame and trunk segment (pelvis, lower spine, chest; each in its own
// frame from the fit) seen within max_side_deg of side-on by the fitted heading: the person's
// points whose nearest capsule (body_fit.h's signed distance) is one of the segment's, within
// max_distance_m of it, are cut into slices along the segment's axis (slice_m, at least two
// grid rows at the points' depth); a slice's width is
// the extent of its points across the line of sight plus one grid spacing (the points sample
// the silhouette every grid step, so the extent falls short of it by about that), and w is half
// the median width over the slices with at least min_slice_points points whose two extreme
// points are true silhouette edges: two grid spacings beyond each, outwards, the pixel is not
// the person's or reads at least min_edge_gap_m deeper (a swinging near arm in front of the
// trunk's edge, or the image's edge cutting the trunk, would make the slice read narrow). A
// segment that shows fewer than min_slices such slices gives nothing.
// TorsoDepthCollector keeps these widths and, after side_frames frames with at least one,
// gives their lower quartile (quantile) as the half depth. No |sin theta| correction is
// applied, since the fitted heading is itself off while the depth is wrong (20-30 degrees in
// CesiumMan's side views); a view off side-on only reads wider (w >= r, by at most
// s |sin max_side_deg|), and the edge rule keeps occluded slices from reading narrower, so a
// low quantile is the closer estimate: the median read 0.6-1.6 cm deeper than the procedural
// body's 20-22 cm on its CMU walks, the lower quartile 21.4-22.1.

#include <optional>
#include <vector>

#include "capture-client/tracker/articulated_body.h"
#include "capture-client/tracker/person_detector.h"
#include "common/geometry/pinhole_camera.h"

namespace reenact::capture {

struct TorsoDepthOptions {
  double max_distance_m = 0.1;  // points farther from every trunk capsule are not the trunk's, > 0
  double slice_m = 0.03;        // least slice height, > 0
  int min_slice_points = 3;     // >= 2
  int min_slices = 2;           // >= 1
  // A slice's edge counts only where the silhouette ends beyond it: the person pixel there,
  // if any, lies at least this far behind the edge (metres, >= 0).
  double min_edge_gap_m = 0.1;
  double max_side_deg = 30;  // [0, 90]; 90: every view
  int side_frames = 10;      // frames with a side view before the depth is given; >= 1
  // The half depth given: this nearest-rank quantile of the collected widths, [0, 1].
  double quantile = 0.25;
  // The depth is kept within [min_depth_ratio, 1] of the breadth (a trunk deeper than broad
  // becomes one capsule, s = 0), 0 < min_depth_ratio <= 1.
  double min_depth_ratio = 0.4;

  void Check() const;
};

// One trunk segment's silhouette half width across the line of sight in one frame.
struct TrunkWidth {
  BodySegment segment = BodySegment::kLowerSpine;
  double half_width_m = 0;   // w above
  double sin_from_side = 0;  // |sin theta| of the fitted segment, 0 side-on, 1 facing
};

// The widths of the trunk segments seen within max_side_deg of side-on in one frame: blob,
// the frame's person (its grid on `camera`); posed, the body's fitted pose on it. Segments
// seen along their axis (the horizontal part of the line of sight under a third of it),
// behind the sensor, or with too few slices whose edges are free are left out; no person, no
// points or a blob without its grid images: none. The points are looked at only when a
// segment is seen near side-on.
std::vector<TrunkWidth> MeasureTrunkWidths(const ArticulatedBody& body, const PosedBody3& posed,
                                           const PersonBlob& blob, const PinholeCamera& camera,
                                           const TorsoDepthOptions& options = {});

// The shape with the trunk's half depth set to half_depth_m and its breadth kept: torso_radius
// = half_depth_m, torso_half_spread = the old radius + spread - half_depth_m, the half depth
// first kept within [min_depth_ratio, 1] of the half breadth. half_depth_m > 0 (CHECK).
BodyShape WithTorsoDepth(const BodyShape& shape, double half_depth_m, double min_depth_ratio = 0.4);

// The trunk's breadth from the calibration pose. The calibration frame faces the sensor with the
// arms held out above the abdomen and the legs below it, so the abdomen (the lower spine
// segment, waist -> torso joint) shows its whole breadth: seen facing (|sin theta| = 1),
// w = r + s. The chest does not: its slices run into the arms or, above them, the neck; nor
// does the pelvis once its capsules are as narrow as the body, since its edges then meet the
// thighs'. One breadth serves the three segments (BodyShape has one). The shape's prior,
// average-adult proportions, make CesiumMan's trunk 24.6-27.3 cm broad against its mesh's
// 20.5-22.7 cm at the abdomen, and capsules that broad take a hanging arm's points.
// Returns the lower spine's half width (MeasureTrunkWidths with every view allowed), metres,
// when the segment is seen within max_facing_deg of facing the sensor (|sin theta| at least
// cos max_facing_deg) and shows at least options.min_slices slices whose edges are free;
// otherwise nothing (also for every degenerate input MeasureTrunkWidths rejects).
// 0 <= max_facing_deg <= 90 (CHECK).
std::optional<double> MeasureTrunkBreadth(const ArticulatedBody& body, const PosedBody3& posed,
                                          const PersonBlob& blob, const PinholeCamera& camera,
                                          double max_facing_deg = 30,
                                          const TorsoDepthOptions& options = {});

// The shape with the trunk's half breadth set to half_breadth_m and its half depth kept:
// torso_half_spread = half_breadth_m - torso_radius; a breadth under the depth gives a round
// trunk of that breadth (torso_radius = half_breadth_m, spread 0). half_breadth_m > 0 (CHECK).
BodyShape WithTorsoBreadth(const BodyShape& shape, double half_breadth_m);

// Collects the side views of a track (above) until it has the half depth.
class TorsoDepthCollector {
 public:
  explicit TorsoDepthCollector(const TorsoDepthOptions& options = {});

  // Adds a frame's widths (MeasureTrunkWidths'; non-positive or non-finite ones are left
  // out); returns the half depth (metres, the quantile of every width kept) on the frame that
  // completes side_frames frames with a width, and nothing before or after it.
  std::optional<double> Add(const std::vector<TrunkWidth>& widths);
  // Whether the half depth has been given.
  bool done() const { return done_; }
  void Clear();

 private:
  TorsoDepthOptions options_;
  std::vector<double> half_widths_;
  int frames_ = 0;
  bool done_ = false;
};

}  // namespace reenact::capture
