#pragma once
// ORB features of one RGB-D frame for SLAM: keypoints on the static background only (a
// person mask, grown by mask_dilation_px, is excluded from detection so the subject never
// becomes a map point), each with its undistorted normalised coordinates and, where the
// registered depth is reliable, its depth and 3D position in the camera frame (OpenCV
// camera axes, metres).
//
// Detection is spread over the image: candidate_factor * num_features candidates are
// detected, the image is cut into grid_cell_px cells, and cells take turns giving up their
// strongest remaining candidate until num_features are kept, so that texture-rich corners
// do not take every feature. A depth reading is reliable when the 3x3 neighbourhood of the
// keypoint's pixel has readings that all lie within depth_edge_ratio of the centre's (not on
// a depth discontinuity, where the pixel may belong to either surface), within
// [min_depth_m, max_depth_m]; with depth_fit_radius_px a plane through the readings around
// it then gives the depth.

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "vision/pose/observation_model.h"

namespace reenact::vision {

struct OrbFeatureOptions {
  int num_features = 1000;    // keypoints kept per frame, >= 1
  double scale_factor = 1.2;  // ORB pyramid scale, in (1, 2]
  int num_levels = 8;         // ORB pyramid levels, [1, 16]
  int fast_threshold = 20;    // FAST threshold, [1, 255]
  // Candidates detected before spreading: candidate_factor * num_features, >= 1.
  double candidate_factor = 2.0;
  int grid_cell_px = 40;      // cell side for spreading keypoints, >= 8
  int mask_dilation_px = 15;  // person mask grown by this many pixels, >= 0
  double min_depth_m = 0.3;   // depth readings used, metres; 0 < min < max
  double max_depth_m = 6.0;
  double depth_edge_ratio = 0.03;  // (0, 1)
  int depth_edge_radius_px = 1;    // half side of the window checked, [0, 16]
  // Depth of a keypoint with a reliable reading: 0 = that reading; r > 0 = a plane fitted in
  // inverse depth to the (2r+1)^2 window (depth_plane_fit.h, tolerance depth_edge_ratio),
  // evaluated at the sub-pixel keypoint, where the fit is trusted. [0, 16]. Default 0 (the
  // SLAM's figures were measured with single readings); the clip map uses 4.
  int depth_fit_radius_px = 0;
  // Sub-pixel keypoints: each keypoint moved to the gradient-weighted corner position
  // (subpixel_corner.h, cv::cornerSubPix's iteration, in a window of half side 2 s,
  // s = scale_factor^octave) on the full image, kept when it stays within 2 s (else the
  // whole-pixel position stays). FAST's own
  // keypoints sit 1-2 px inside a corner. Default off: the SLAM's figures were measured
  // without it; the clip map and the viewer's relocaliser turn it on.
  bool subpixel = false;

  void Check() const;
};

struct FrameFeatures {
  // Pixel positions in the (distorted) image, pixel centres at integers: OpenCV's level
  // coordinates x_l map to (x_l + 1/2) s - 1/2 with s = scale_factor^octave (OpenCV's own
  // x_l s is biased by (s - 1) / 2 towards the top-left, up to 1.3 px at level 7).
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;                            // CV_8UC1, one 32-byte row per keypoint
  std::vector<KeypointObservation> observations;  // per keypoint: normalised, depth, octave
  std::vector<Eigen::Vector3d> points_in_camera;  // per keypoint; valid when depth_m > 0

  size_t size() const { return keypoints.size(); }
  int CountWithDepth() const;
  const uint8_t* Descriptor(size_t i) const {
    return descriptors.ptr<uint8_t>(static_cast<int>(i));
  }
};

// CPU time of ExtractOrbFeatures' steps, milliseconds (CpuMs(): the process's CPU time, so a
// loaded machine's other processes do not count).
struct OrbTimings {
  double detect_ms = 0;    // OpenCV's ORB: pyramid, FAST, Harris score, orientation, descriptors
  double spread_ms = 0;    // spreading over the grid
  double subpixel_ms = 0;  // sub-pixel refinement
  double rest_ms = 0;      // mask, undistortion, depth, copies
};

// Features of one frame. gray: CV_8UC1 of the camera's size; depth registered to it;
// person_mask (255 = subject) may be null. Preconditions (CHECK): sizes agree, options valid.
// timings (optional) receives the CPU time of each step.
FrameFeatures ExtractOrbFeatures(const cv::Mat& gray, const ImageDepthMm& depth,
                                 double depth_scale_m, const ImageGray8* person_mask,
                                 const PinholeCamera& camera, const OrbFeatureOptions& options,
                                 OrbTimings* timings = nullptr);

// The process's CPU time in milliseconds (std::clock), for per-stage profiles.
double CpuMs();

// Hamming distance between two 256-bit ORB descriptors.
int DescriptorDistance(const uint8_t* a, const uint8_t* b);

}  // namespace reenact::vision
