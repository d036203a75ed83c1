#pragma once
// The viewer's own camera: where the frames the relocaliser and the AR compositor work on
// come from, and its intrinsics.
//
//   tum:DIR       a TUM RGB-D sequence's colour images in time order (rgb.txt, or the colour
//                 columns of associations.txt; tum_directory_source.h)
//   video:FILE    a video file (OpenCV VideoCapture: whatever FFmpeg decodes)
//   live[:N]      camera N (default 0) through OpenCV VideoCapture
//   synthetic:SCENARIO[?...]  a viewer walking around an [Eval] scene, with the true pose of
//                 every frame (synthetic_camera_source.h; intrinsics from the scene)
//
// Intrinsics of real cameras always come from a calibration file (camera_calibration.h):
// --calibration FILE, or for tum:DIR the file DIR/calibration.yaml when present (docs/calibration/
// has the TUM Kinects'). Frames must have the calibration's size.

#include <Eigen/Geometry>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "common/error/expected.h"
#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"

namespace reenact::viewer {

struct CameraFrame {
  double timestamp_s = 0;  // the source's clock (TUM: its timestamp; video: position)
  ImageRgb8 color;         // R G B, the calibration's size
  // The camera's true pose in the clip's world frame (OpenCV axes), where the source knows it
  // (synthetic:); evaluations compare the relocalised pose with it.
  std::optional<Eigen::Isometry3d> true_world_from_viewer;
};

class CameraSource {
 public:
  virtual ~CameraSource() = default;
  // "tum:DIR", "video:FILE", "live:0", "synthetic:turn-and-kick (...)".
  virtual std::string description() const = 0;
  virtual const PinholeCamera& camera() const = 0;
  // The next frame; nullopt at the end of a file or sequence. Errors: a frame that cannot be
  // read or decoded, or of another size than the calibration (the message says which).
  virtual Expected<std::optional<CameraFrame>> Next() = 0;
};

// Opens a source from its spec (above). calibration: the --calibration file, if given.
// Errors: "usage" for an unknown or malformed spec, a missing calibration (saying how to give
// one); those of LoadCameraCalibration; "not_found" for a missing directory or file;
// "unavailable" for a live camera that cannot be opened or delivers no frame; "usage" for a
// calibration given to synthetic: (its intrinsics are the scene's); those of
// OpenSyntheticCameraSpec.
Expected<std::unique_ptr<CameraSource>> OpenCameraSource(
    std::string_view spec, const std::optional<std::filesystem::path>& calibration);

}  // namespace reenact::viewer
