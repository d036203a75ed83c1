#pragma once
// Map points for viewpoints the capture never had. ORB descriptors change with the viewing
// direction: a viewer who walks 30-45 degrees around the subject sees the room's walls at
// another slant, and matches against descriptors taken from the capture's viewpoint fall from
// hundreds to a few dozen (reenact-eval reloc). From an RGB-D keyframe we can render how the
// static background would look from such a viewpoint (depth-image-based rendering) and take
// ORB features there too, so the map carries descriptors for the views viewers will have.
//
// Virtual viewpoints turn the keyframe's sensor about the vertical line (up_in_world) through
// a pivot (the subject's centre, where viewers look) by each of yaw_deg, keeping its
// distance, height and aim at the pivot: exactly the capture camera walked around the
// subject.
//
// Rendering (RenderVirtualView): the keyframe's depth, without the person (mask grown by
// person_dilation_px), is forward-projected into the virtual camera with a z-buffer; cracks
// (pixels without a reading whose 3x3 neighbourhood has at least crack_min_neighbours
// readings) are filled with the median of those readings, twice; every pixel with depth then
// takes its colour by looking back into the keyframe (bilinear). Pixels without depth are
// holes: disocclusions behind the subject and furniture, and what the keyframe never saw.
// Features (VirtualViewFeatures) are taken away from holes (grown by hole_margin_px), so
// that hole borders, which are not in the room, never become map points; each keypoint's 3D
// point is lifted with the rendered depth as the map's own features are.
//
// Frames: world_from_sensor as the recorder's (world metres); cameras with OpenCV axes. The
// virtual camera has the keyframe camera's intrinsics without distortion.

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "capture-client/map/background_map_builder.h"
#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "common/skeleton/skeleton.h"
#include "proto/clip/map_codec.h"
#include "vision/features/orb_features.h"

namespace reenact::capture {

struct VirtualViewOptions {
  // Turns about the vertical through the pivot, degrees, each in [-90, 90] and not 0; empty
  // = no virtual views. Default +-20 and +-40: viewers walk up to about 45 degrees around
  // the subject.
  std::vector<double> yaw_deg = {-40, -20, 20, 40};
  int person_dilation_px = 4;    // >= 0
  int crack_min_neighbours = 4;  // [1, 8]
  int hole_margin_px = 8;        // >= 0
  // The map's features (mask_dilation_px is replaced by hole_margin_px).
  vision::OrbFeatureOptions features = DefaultMapFeatures();
  // While recording: a keyframe for virtual views every keyframe_interval stored frames
  // (>= 1), at most max_keyframes of them (>= 0), kept in memory and rendered at the end.
  // Each takes about 0.15 s (4 views at 640x480).
  int keyframe_interval = 60;
  int max_keyframes = 6;

  void Check() const;
};

struct VirtualView {
  ImageRgb8 color;     // holes black
  ImageDepthMm depth;  // in the keyframe depth's units (depth_scale_m); 0 = hole
  Eigen::Isometry3d world_from_camera = Eigen::Isometry3d::Identity();
  PinholeCamera camera;  // the keyframe's intrinsics, no distortion
};

// The sensor turned by yaw_deg about the vertical through pivot_in_world (both world frame);
// up_in_world need not be unit length. Degenerate input (a zero up vector) gives the sensor's
// pose unchanged.
Eigen::Isometry3d TurnAboutVertical(const Eigen::Isometry3d& world_from_sensor,
                                    const Eigen::Vector3d& pivot_in_world,
                                    const Eigen::Vector3d& up_in_world, double yaw_deg);

// Renders the keyframe (colour and registered depth in units of depth_scale_m, person mask
// 255 = subject, may be empty) as seen from world_from_virtual. The result's depth has the
// same units. Preconditions (CHECK): sizes agree, valid options, depth_scale_m > 0.
VirtualView RenderVirtualView(const ImageRgb8& color, const ImageDepthMm& depth,
                              double depth_scale_m, const ImageGray8& person_mask,
                              const PinholeCamera& camera,
                              const Eigen::Isometry3d& world_from_sensor,
                              const Eigen::Isometry3d& world_from_virtual,
                              const VirtualViewOptions& options);

struct VirtualMapPoint {
  Eigen::Vector3d position_in_world = Eigen::Vector3d::Zero();
  std::array<uint8_t, 32> descriptor{};
};

// Features of every virtual view of one keyframe (see the top of this file), in the world
// frame. pivot_in_world: what the viewers look at (the subject's centre).
std::vector<VirtualMapPoint> VirtualViewFeatures(
    const ImageRgb8& color, const ImageDepthMm& depth, double depth_scale_m,
    const ImageGray8& person_mask, const PinholeCamera& camera,
    const Eigen::Isometry3d& world_from_sensor, const Eigen::Vector3d& pivot_in_world,
    const Eigen::Vector3d& up_in_world, const VirtualViewOptions& options);

// A recorded frame kept for virtual views.
struct VirtualViewKeyframe {
  ImageRgb8 color;
  ImageDepthMm depth;  // registered to color
  ImageGray8 person_mask;
  Eigen::Isometry3d world_from_sensor = Eigen::Isometry3d::Identity();
  Eigen::Vector3d pivot_in_world = Eigen::Vector3d::Zero();  // the subject's centre
};

// The subject's centre for virtual views: the waist, else the torso, else the mean of the
// joints present, moved into the world; nullopt for a skeleton without joints.
std::optional<Eigen::Vector3d> SubjectPivot(const Skeleton& skeleton_in_sensor,
                                            const Eigen::Isometry3d& world_from_sensor);

// The map with the virtual views' features of every keyframe merged in (merge rules of
// BackgroundMapBuilder::AddPoint with `merge`). points_added: how many new points.
proto::ClipMap AddVirtualViews(proto::ClipMap map,
                               const std::vector<VirtualViewKeyframe>& keyframes,
                               double depth_scale_m, const PinholeCamera& camera,
                               const Eigen::Vector3d& up_in_world,
                               const VirtualViewOptions& options, const BackgroundMapOptions& merge,
                               size_t* points_added = nullptr);

}  // namespace reenact::capture
