#pragma once
// Person detection in depth without a skeleton (the tracker's first step):
//  1. Floor: a RANSAC plane (segment/floor_plane.h) through the points at least
//     floor_below_sensor_m below the sensor along the up direction (the world's up when the
//     frame knows its pose, else the image's up, -y: a sensor held roughly level, tilted at
//     most floor_max_tilt_deg). Cached (in the world frame when the pose is known, else in
//     the sensor frame) and re-fitted when it stops fitting.
//  2. Candidates on a grid of every grid_step_px-th pixel: readings in range, above the floor
//     by more than its clearance and at most max_height_m above it.
//  3. Connected regions (4-connected on the grid) joining neighbours whose depths differ by at
//     most depth_step(z) + grid_step_px z / fx (the depth noise plus a 45-degree slope).
//  4. Merging: regions that touch in the image with a depth gap of at most merge_step_m (an
//     arm in front of the torso, a body split where a limb covers its side; while tracking,
//     tracking_merge_step_m: also a hand raised behind the head) are merged, smallest gap
//     first, as long as the union stays within the size limits below (so a person never
//     merges with a wall or a large object).
//  5. The person: among the merged regions that are human-sized (top between min_top_m and
//     max_height_m above the floor, bottom within max_bottom_m of it unless the region
//     reaches the image's lower edge, horizontal extent at most max_extent_m, area between
//     min_area_m2 and max_area_m2, and, when acquiring a person, at most max_top_width_m
//     wide in its top 12 cm: a head, unlike a cabinet), the one nearest the previous
//     person's centroid when given (within max_jump_m; the top-width test is then left out,
//     as raised arms widen the top), else the largest.
// Without a floor in view (a close-up, a background removed by the sensor's software, a
// sensor aimed level above the floor), steps 2-5 run on every reading in range, the heights
// measured along the up direction above, and a region is human-sized by its own vertical span
// (at least min_top_m, at most max_height_m) instead of its height above the floor. The
// chosen person then stands on a floor of its own (PersonBlob::floor_source): the lowest of
// its lowest points seen so far while it was whole in the image (feet), cached as the floor
// is; or, while the region reaches the image's lower edge and no such floor is known (legs
// out of view), a floor assumed_stature_m below its top.
// Frames: points in the sensor frame (OpenCV axes, metres). Not thread-safe (floor cache).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string_view>
#include <vector>

#include "capture-client/segment/floor_plane.h"
#include "capture-client/segment/pixel_rays.h"
#include "capture-client/segment/segment_options.h"
#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"

namespace reenact::capture {

struct PersonDetectOptions {
  int grid_step_px = 2;      // >= 1
  double min_depth_m = 0.4;  // readings outside [min, max] are holes; 0 <= min < max
  double max_depth_m = 6.0;
  double floor_below_sensor_m = 0.3;  // floor candidates lie this far below the sensor, >= 0
  double max_height_m = 2.4;          // person points at most this high above the floor, > 0
  double min_top_m = 0.5;             // a person's top at least this high, [0, max_height_m)
  double max_bottom_m = 0.5;          // its lowest point at most this high (feet), >= 0
  double max_extent_m = 2.6;          // horizontal extent at most, > 0
  double min_area_m2 = 0.08;          // area facing the sensor, 0 <= min < max
  double max_area_m2 = 3.0;
  double max_top_width_m = 0.6;  // width of the top 12 cm at most, > 0
  double max_jump_m = 0.8;       // centroid movement between frames when tracking, > 0
  int min_region_pixels = 40;    // grid pixels, >= 1
  double merge_step_m = 0.4;     // largest depth gap merged across, >= 0
  // The same while tracking (a previous centroid given), >= 0: the tracker keeps only the
  // points near the body it predicts, so a larger gap can be bridged (a hand raised behind the
  // head, 50-60 cm deeper than the face).
  double tracking_merge_step_m = 0.8;
  // A person's standing height taken where the floor is not in view and its feet have not
  // been seen (an upper body close up), > 0: the average adult's.
  double assumed_stature_m = 1.7;
  // Floor fit and clearance, region-growing depth step: as the person segmenter's.
  PersonSegmentOptions segment;

  void Check() const;
};

enum class DetectStatus {
  kOk = 0,
  kNoDepth,   // no reading in range
  kNoPerson,  // no human-sized region
};
std::string_view DetectStatusName(DetectStatus status);

// Where PersonBlob::floor_in_sensor comes from.
enum class FloorSource {
  kSeen = 0,        // a plane fitted to the floor's readings
  kPersonLowest,    // no floor in view: the person's lowest point (its feet)
  kAssumedStature,  // no floor and no feet in view: assumed_stature_m below the person's top
};
std::string_view FloorSourceName(FloorSource source);

struct PersonBlob {
  DetectStatus status = DetectStatus::kNoDepth;
  int grid_step_px = 1;
  ImageGray8 mask;       // grid-sized (ceil(w / step) x ceil(h / step)), 255 = person
  Image<float> depth_m;  // grid-sized readings in metres, 0 = hole (every pixel)
  std::vector<Eigen::Vector3d> points;  // the person's grid points, sensor frame
  std::vector<Eigen::Vector2i> pixels;  // their grid pixels
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double top_height_m = 0, bottom_height_m = 0;  // above the floor
  double area_m2 = 0;
  int plausible_regions = 0;  // human-sized regions seen (2 or more: the nearest/largest won)
  std::optional<Plane3> floor_in_sensor;  // normal pointing up
  FloorSource floor_source = FloorSource::kSeen;
  bool floor_refitted = false;
  bool touches_bottom = false;  // the person reaches the image's lower edge (legs cut off)
};

class PersonDetector {
 public:
  // Preconditions (CHECK): a valid camera, depth_scale_m > 0, valid options.
  PersonDetector(const PinholeCamera& camera, double depth_scale_m,
                 const PersonDetectOptions& options = {});

  // depth: the camera's size (CHECK). world_from_sensor and world_up (unit, world frame):
  // when the frame knows them. previous_centroid: the person's centroid in the sensor frame
  // on the previous frame, when tracking.
  PersonBlob Detect(const ImageDepthMm& depth,
                    const std::optional<Eigen::Isometry3d>& world_from_sensor = std::nullopt,
                    const std::optional<Eigen::Vector3d>& world_up = std::nullopt,
                    const std::optional<Eigen::Vector3d>& previous_centroid = std::nullopt);

  void ResetFloor() { floor_.reset(), person_floor_.reset(); }
  const PersonDetectOptions& options() const { return options_; }
  const PinholeCamera& camera() const { return camera_; }
  const PixelRays& rays() const { return rays_; }  // camera()'s pixel rays

 private:
  std::optional<Plane3> UpdateFloor(const ImageDepthMm& depth, const Eigen::Vector3d& up,
                                    const std::optional<Eigen::Isometry3d>& world_from_sensor,
                                    bool* refitted);

  // The depth grid's points, their height above the floor and the floor's horizontal axes.
  struct GridPoints {
    int width = 0, height = 0;
    Plane3 floor;
    Eigen::Vector3d e1, e2;
    std::vector<Eigen::Vector3d> point;
    std::vector<double> height_m;
  };
  // A connected region of candidates: its size, extent across the floor and height range.
  struct Region {
    int pixels = 0;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double top = -1e9, bottom = 1e9, area = 0;
    double min1 = 1e9, max1 = -1e9, min2 = 1e9, max2 = -1e9;
    bool touches_bottom = false;
  };
  // Two regions' smallest depth gap where they touch.
  struct Contact {
    double gap;
    int a, b;
  };
  // The grid's readings within range into blob (size, depth); false when there are none.
  bool ReadDepthGrid(const ImageDepthMm& depth, PersonBlob* blob) const;
  // Points and heights of the grid above `floor`; label_ marks the candidates (above the
  // floor and not too high when floor_seen, every reading otherwise).
  GridPoints MarkCandidates(const PersonBlob& blob, const Plane3& floor, bool floor_seen);
  // Regions grown across depth steps of the segmentation's depth_step (label_ set to them).
  std::vector<Region> GrowRegions(const GridPoints& grid);
  // Touching regions within merge_step of each other, smallest gap first.
  std::vector<Contact> RegionContacts(const GridPoints& grid, double merge_step) const;
  // Merges across the contacts while the union stays human-sized; returns each region's
  // parent (itself for a merged region's root), label_ set to the roots.
  std::vector<int> MergeRegions(const GridPoints& grid, double merge_step,
                                std::vector<Region>* regions);
  // The plausible person region (the largest, or the nearest to previous_centroid), -1: none.
  int ChooseRegion(const GridPoints& grid, const std::vector<Region>& regions,
                   const std::vector<int>& parent,
                   const std::optional<Eigen::Vector3d>& previous_centroid, bool floor_seen,
                   PersonBlob* blob) const;
  // Without a floor in view: the person's own floor for the chosen region (class comment);
  // moves r's heights onto it.
  Plane3 PersonFloor(const GridPoints& grid, int id, const Eigen::Vector3d& up,
                     const std::optional<Eigen::Isometry3d>& world_from_sensor, Region* r,
                     FloorSource* source);
  void FillBlob(const GridPoints& grid, const Region& r, int id, PersonBlob* blob) const;

  struct CachedFloor {
    Plane3 plane;
    bool in_world = false;
    double inlier_ratio = 0;
  };
  PinholeCamera camera_;
  PixelRays rays_;  // camera_'s, computed once
  double depth_scale_m_;
  PersonDetectOptions options_;
  std::optional<CachedFloor> floor_;
  std::optional<CachedFloor> person_floor_;  // the lowest feet seen without a floor in view
  std::vector<int> label_, queue_;
};

}  // namespace reenact::capture
