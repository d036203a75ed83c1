#pragma once
// Geodesic extremities of a person's depth region (for re-initialising after a loss):
// the head, the hands and the feet are the points of the visible surface farthest from the
// torso along the surface, whatever the pose.
//  1. Nodes: the person's points thinned to one per voxel_m cube (the mean of the points in
//     it), so the graph's size does not grow with the resolution or nearness of the sensor.
//  2. Graph: an edge between every two nodes at most neighbour_m apart in 3D, weighted by
//     their distance. An arm in front of the torso is joined to it only where it touches it
//     in 3D (at the shoulder), not across the depth gap that the image shows as adjacency.
//  3. Geodesic distance (Dijkstra) from the torso centre: the node nearest the nodes'
//     centroid. Nodes it cannot reach (a fragment not joined to the body) take no part.
//  4. Extremities: the local maxima of the geodesic distance that stand out by at least
//     min_prominence_m (topological persistence: from the peak, every path to a farther
//     peak first descends by that much; a shoulder's corner on the way up the neck, a
//     noisy bump, do not), farthest first, each kept when it lies at least min_length_m
//     from the centre and at least min_separation_m (geodesic) from every extremity kept
//     before it (a hand's fingers and knuckles give one extremity), at most
//     max_extremities.
//  5. Labels, in the floor's frame (up = the floor's normal; H = the region's top above the
//     floor): the head is the extremity rising at least head_min_rise_m above the centre
//     with the shortest geodesic length (a raised or outstretched hand reaches farther along
//     the surface than the head); feet are the (at most two) lowest of the others within
//     foot_max_height_ratio H of the floor; hands are the (at most two) others with the
//     longest geodesic lengths; the rest stay unlabelled. Left and right are not labelled:
//     they depend on the heading, which the caller tries (extremity_pose.h).
// Frames: the sensor frame (OpenCV axes, metres). Non-finite points are skipped.

#include <Eigen/Core>
#include <optional>
#include <string_view>
#include <vector>

#include "capture-client/segment/floor_plane.h"

namespace reenact::capture {

struct GeodesicExtremityOptions {
  double voxel_m = 0.02;                // node spacing, > 0
  double neighbour_m = 0.045;           // edge length at most, > voxel_m
  double min_length_m = 0.2;            // geodesic length of an extremity at least, >= 0
  double min_separation_m = 0.3;        // geodesic distance between extremities at least, > 0
  double min_prominence_m = 0.1;        // a peak's persistence at least, >= 0
  int max_extremities = 6;              // >= 1
  double head_min_rise_m = 0.15;        // head above the torso centre at least, >= 0
  double foot_max_height_ratio = 0.25;  // feet within this share of H of the floor, [0, 1]

  void Check() const;
};

enum class ExtremityLabel { kUnknown = 0, kHead, kHand, kFoot };
std::string_view ExtremityLabelName(ExtremityLabel label);

struct Extremity {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // a node (voxel mean), sensor frame
  double geodesic_m = 0;                               // from the torso centre
  double height_m = 0;                                 // above the floor (0 without a floor)
  ExtremityLabel label = ExtremityLabel::kUnknown;
};

struct GeodesicExtremities {
  // false: no finite point (every field then at its default).
  bool valid = false;
  Eigen::Vector3d torso_centre = Eigen::Vector3d::Zero();
  int nodes = 0;                       // after thinning
  int reachable = 0;                   // nodes joined to the torso centre
  std::vector<Extremity> extremities;  // farthest (geodesic) first

  // The extremities with a label, farthest first.
  std::vector<const Extremity*> WithLabel(ExtremityLabel label) const;
};

// floor: normal pointing up; without it, up = the image's up (-y) and heights are relative to
// the lowest node (so feet are found on a region standing on an unseen floor).
GeodesicExtremities FindGeodesicExtremities(const std::vector<Eigen::Vector3d>& points,
                                            const std::optional<Plane3>& floor,
                                            const GeodesicExtremityOptions& options = {});

}  // namespace reenact::capture
