#pragma once
// Assigning a person mask's pixels to body parts by their projected axes, as the model fits
// do (radius_fit.h, cross_section_fit.h): a pixel goes to the part whose projected axis
// segment is nearest in the image, measured across the segment (in pixels, or relative to
// the part's projected radius: ProjectedPartAxis::distance_unit_*); a pixel whose foot on a
// part's axis line falls beyond either end of the segment is no candidate for that part, and
// a pixel beyond the ends of every segment (and their end bands) goes to no part. Ties go to the
// lower part index. The projected axis is the straight segment between the projections of the axis
// ends (exact for an undistorted camera).

#include <Eigen/Core>
#include <array>
#include <optional>

#include "common/geometry/pinhole_camera.h"
#include "common/skeleton/skeleton.h"

namespace reenact {

struct ProjectedPartAxis {
  Eigen::Vector2d a;       // pixel of the axis end a
  Eigen::Vector2d b;       // pixel of the axis end b
  Eigen::Vector2d dir;     // unit, a -> b in the image
  Eigen::Vector2d normal;  // unit, (-dir.y, dir.x): dir turned by +90 degrees
  double length_px = 0;    // |b - a|, pixels
  // The unit in which AssignPixelToPart measures a pixel's distance from this axis, at the a
  // and b ends and linear in t between them. 1 (pixels) by default; a part's projected radius
  // r f / z at either end (f / z is linear in t along a projected segment) makes the distance
  // relative to the part's thickness, so a wide torso keeps its pixels next to a thin arm.
  double distance_unit_a = 1;
  double distance_unit_b = 1;
  // How far past the a and b ends (pixels along the axis) a pixel's foot may lie and the
  // pixel still be a candidate for this part (at t 0 or 1, distance measured across the axis
  // as within the segment): where the part's silhouette runs past its projected end, as the
  // near rim of an end disc does in perspective. 0 by default: the plain segment.
  double end_band_a_px = 0;
  double end_band_b_px = 0;
  // For assignment by depth as well: the axis ends' depths (camera z, metres, > 0) and the
  // part's radius (metres). radius_m 0 (the default), or an end depth not > 0, leaves depth
  // out for this axis.
  double depth_a_m = 0;
  double depth_b_m = 0;
  double radius_m = 0;
};

using ProjectedPartAxes = std::array<std::optional<ProjectedPartAxis>, kBodyPartCount>;

// The axis a -> b (camera frame, metres) in the image; nullopt if either end is not in front
// of the camera (PinholeCamera::Project) or the projected segment is shorter than
// min_length_px.
std::optional<ProjectedPartAxis> ProjectPartAxis(const Eigen::Vector3d& a_in_camera,
                                                 const Eigen::Vector3d& b_in_camera,
                                                 const PinholeCamera& camera,
                                                 double min_length_px = 2.0);

struct PartPixelAssignment {
  int part = -1;         // Index(BodyPart)
  double t = 0;          // in [0, 1]: the pixel's foot along the projected axis (clamped)
  double offset_px = 0;  // signed distance from the axis line along the axis's normal
};

// The part a pixel goes to (see above; distance |offset| / unit); nullopt if it is beyond the
// ends of every axis (and their end bands). With the pixel's depth reading depth_m > 0, the
// distance to an axis with radius_m > 0 is instead the pixel's distance, in radii, from the
// half of that part's plain cylinder that faces the camera: with o = |offset| / unit and
// d = (depth_m - z(t)) / r (> 0: behind the axis), 1 / z(t) = (1 - t) / depth_a_m + t / depth_b_m,
//   | sqrt(o^2 + d^2) - 1 |  where d <= 0,   sqrt((o - 1)^2 + d^2)  where d > 0
// (in the orthographic limit the visible surface is the half circle o^2 + d^2 = 1, d <= 0; 1 / z
// is linear in t along a projected segment). So a forearm held in front of the belly keeps
// its pixels although the torso's axis runs right behind them, and an arm's root behind the
// torso's edge is not taken for torso.
std::optional<PartPixelAssignment> AssignPixelToPart(const Eigen::Vector2d& pixel,
                                                     const ProjectedPartAxes& axes,
                                                     double depth_m = 0);

}  // namespace reenact
