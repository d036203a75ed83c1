#pragma once
// Options of the person segmentation (person_segmenter.h). Distances in metres, depths z in
// metres along the sensor's optical axis.
//
// Depth-dependent tolerances follow the Kinect v1 error model (Khoshelham and Elberink 2012):
// the axial noise grows with z^2 (sigma ~ 1.4 mm * z^2 per metre^2) and the disparity
// quantisation step too (~ 2.85 mm * z^2), so every tolerance below is
//   tol(z) = base_m + per_z2 * z^2.

#include <cstdint>

namespace reenact::capture {

struct DepthTolerance {
  double base_m = 0;  // metres, >= 0
  double per_z2 = 0;  // metres per metre^2 of depth, >= 0; base_m + per_z2 > 0
  double At(double z) const { return base_m + per_z2 * z * z; }
  void Check(const char* name) const;
};

struct PersonSegmentOptions {
  // Depth readings outside [min_depth_m, max_depth_m] are treated as holes.
  // 0 <= min < max. Defaults 0.3 m and 10 m.
  double min_depth_m = 0.3;
  double max_depth_m = 10.0;

  // --- Floor (a RANSAC plane fit over depth points below the feet) ---
  // Remove the floor. Off: no fit; the body bound alone keeps the floor out (worse at feet).
  bool remove_floor = true;
  // Largest angle between the floor's normal and the body's up axis, degrees, (0, 90).
  // Default 40 (a tilted sensor, a leaning skeleton).
  double floor_max_tilt_deg = 40;
  // Floor candidates: depth points within floor_search_band_m (along up) of the floor height
  // guessed from the skeleton (ankles about 8 cm above it) and within floor_search_radius_m
  // (across up) of the feet. > 0. Defaults 0.35 m and 2.5 m.
  double floor_search_band_m = 0.35;
  double floor_search_radius_m = 2.5;
  // Every floor_sample_stride_px-th pixel in x and y is a candidate; >= 1. Default 4.
  int floor_sample_stride_px = 4;
  // A candidate p is an inlier of a plane (normal n) when its distance to it is at most
  // base_m + per_z2 z^2 |n . p| / z, the depth noise across the plane (see floor_clearance).
  // Default 1 cm + 5 mm/m^2: 2.9 cm for floor 3 m ahead of a sensor 1.3 m high.
  DepthTolerance floor_fit{0.01, 0.005};
  // A floor needs at least floor_min_inliers inlier candidates (>= 3, default 150) and at
  // least floor_min_inlier_ratio of all candidates (in [0, 1], default 0.25: a plane that
  // merely cuts through the floor along a strip holds far fewer).
  int floor_min_inliers = 150;
  double floor_min_inlier_ratio = 0.25;
  // The cached plane is kept while its inlier ratio among this frame's candidates stays at or
  // above floor_keep_ratio times the ratio it had when fitted; (0, 1]. Default 0.8.
  double floor_keep_ratio = 0.8;
  // RANSAC trials at most; >= 1. Default 300. Seed of the fit; the result is deterministic.
  int floor_max_trials = 300;
  uint64_t floor_seed = 7;
  // A pixel whose point p lies less than base_m + per_z2 z^2 |n . p| / z above the plane
  // (normal n), or below it, is floor, never person: a depth error dz moves p along its ray,
  // across the floor by dz |n . p| / z, which shrinks as the view grazes the floor (0.43 for
  // feet 3 m from a sensor 1.3 m high). Default 8 mm + 5 mm/m^2 (three times the Kinect's
  // axial noise and quantisation error): 2.7 cm at the feet 3 m away.
  DepthTolerance floor_clearance{0.008, 0.005};

  // --- Seeds along the projected bones ---
  // Spacing of the seed samples along each projected bone, pixels, >= 0.5. Default 2.
  double seed_step_px = 2;
  // A sample seeds when the depth seen there lies within [z - seed_in_front_m - noise,
  // z + seed_behind_m + noise] of the bone point's depth z (joints lie inside the body, so
  // its surface is in front of them), noise = depth_step(z). >= 0. Defaults 0.2 m, 0.05 m.
  double seed_in_front_m = 0.2;
  double seed_behind_m = 0.05;

  // --- Region growing ---
  // Neighbouring pixels (4-connected) join when their depths differ by at most
  // depth_step(z). Default 2 cm + 8 mm/m^2: 3.8 cm at 1.5 m, 10 cm at 3 m (independent
  // per-pixel Kinect noise of sigma 1.3 cm and 2.6 cm quantisation steps at 3 m).
  DepthTolerance depth_step{0.02, 0.008};
  // Every mask point lies within body_margin_m of a bone (a capsule per bone), which also
  // covers hands, feet and the top of the head beyond their joints; > 0. Default 0.3 m.
  double body_margin_m = 0.3;
  // Points within core_radius_m of a bone join the region across a depth step too: the
  // sliver of a limb seen behind a nearer one. [0, body_margin_m]; 0 = off. Default 0.1 m.
  double core_radius_m = 0.1;

  // --- Hole filling (mask_fill.h) ---
  // Runs of pixels without a reading along a row, at most max_hole_run_px long (>= 0, 0 =
  // off; default 48), join the mask when the surface at their farther end is in it (the
  // projector's shadow falls on the farther surface).
  int max_hole_run_px = 48;
  // Background regions enclosed by the mask join it when at least hole_person_ratio of their
  // pixels have readings at the surrounding mask's depth (not behind it by more than
  // depth_step, not floor): noise specks go in, a view through a gap stays out. (0, 1].
  // Default 0.5.
  double hole_person_ratio = 0.5;

  // Throws CheckError naming the first field out of range.
  void Check() const;
};

}  // namespace reenact::capture
