#pragma once
// Frame sources of the capture client: one interface for every RGB-D input. Each frame holds
// colour and depth registered to it (same pixel grid), timestamped; sources that know more
// (the synthetic scene's ground truth) fill the optional fields.

#include <memory>
#include <optional>
#include <string>

#include <Eigen/Geometry>

#include "common/error/expected.h"
#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "common/skeleton/skeleton.h"

namespace reenact::capture {

struct SensorInfo {
  std::string description;       // e.g. "synthetic:turn-and-kick (seed 1)"
  PinholeCamera color_camera;    // intrinsics of the colour image
  PinholeCamera depth_camera;    // intrinsics of the depth image (registered: equal to colour)
  double depth_scale_m = 0.001;  // metres per depth unit
  double frame_rate_hz = 30;
  int frame_count = -1;          // frames the source will yield, -1 if unknown (live)
  // World frame's up direction if the source knows it (synthetic ground truth).
  std::optional<Eigen::Vector3d> world_up;
  // Rolling shutter of the colour camera: readout time / frame interval in [0, 1]; 0 for a
  // global shutter or rendered images. The SLAM compensates it (slam/rolling_shutter.h).
  double color_readout_ratio = 0;
  // Standard deviation of a depth reading at 1 m, metres (it grows with the square of the
  // distance); 0 = unknown: the SLAM then keeps its default, made for real Kinect-class
  // sensors, whose depth also suffers registration and timing errors.
  double depth_sigma_1m_m = 0;
  // Whether frames carry colour. A depth-only source (rgbd:DIR without colour images) yields
  // frames with an empty colour image: tracking reads depth only, but a clip needs colour.
  bool has_color = true;
};

struct SensorFrame {
  double timestamp_s = 0;
  ImageRgb8 color;  // empty when the source has no colour (SensorInfo.has_color)
  ImageDepthMm depth;
  // Ground truth or externally known values; absent for sources that do not know them.
  std::optional<Eigen::Isometry3d> world_from_sensor;
  std::optional<Skeleton> skeleton_in_world;
  std::optional<ImageGray8> person_mask;  // 255 = subject
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  virtual const SensorInfo& info() const = 0;
  // The next frame, nullopt at the end of the stream, or an Error (device lost, bad file).
  virtual Expected<std::optional<SensorFrame>> Next() = 0;
};

// Opens a source from its command-line form: synthetic:SCENARIO[?body=FILE.glb] (see
// SyntheticSource::OpenSpec), oni:FILE, openni[:URI], tum:DIR, clip:DIR, rgbd:DIR[?OPTIONS]
// (a folder of depth PNGs, optional colour and a calibration file: rgbd_folder_source.h). An
// unknown or unavailable kind is an Error that says what is accepted.
Expected<std::unique_ptr<FrameSource>> OpenFrameSource(const std::string& spec);

}  // namespace reenact::capture
