#pragma once
// FrameSource over a folder of RGB-D images, any sensor's export (rgbd:DIR), e.g. a UTD-MHAD
// sequence (../shared/data/utd-mhad/aA_sS_t1, read with mirrored=1).
//
// Layout:
//   DIR/depth/NAME.png   16-bit single-channel PNGs, one per frame, in the order of their names
//                        (numerically when every name is a number: 000000.png, 000001.png,
//                        ...; numbered frames must not skip a number). Other files are ignored.
//   DIR/rgb/ or DIR/color/ (optional, not both): the colour image of each depth image under the
//                        same name, NAME.png, NAME.jpg or NAME.jpeg, registered to the depth
//                        (same pixel grid, same size). Without a colour folder the frames carry
//                        an empty colour image and SensorInfo.has_color is false.
//   the camera           ?calibration=FILE, else the one of DIR/camera.json,
//                        DIR/calibration.yml, .yaml, .json that exists (camera_calibration_file.h:
//                        intrinsics as the images are stored, optionally the depth unit, frame
//                        rate, frame count and mirroring).
//
// Options (rgbd:DIR?depth_unit=0.001&fps=30&mirrored=1):
//   depth_unit=M   metres per depth unit; default the file's depth_unit_m, else 0.001
//   fps=F          frames per second; default the file's fps, else 30
//   mirrored=0|1   default the file's mirrored, else 0. 1: the images are mirrored left-right
//                  (the Kinect SDK's, UTD-MHAD's) and are flipped to a true camera's:
//                  pixel (u, v) of the file is (W-1-u, v) of the frame, and the intrinsics
//                  follow: cx' = W-1-cx, p2' = -p2 (the same lens seen in a mirror).
//   undistort=both|color|none  with non-zero distortion: remap colour (bilinear) and depth
//                  (nearest neighbour) to the undistorted camera (both, the default: the
//                  calibration describes the one pixel grid both share), only colour (color: as
//                  tum: does for depth registered by its driver; without colour, as none) or
//                  neither (none: the cameras keep their distortion); ImageUndistorter.
//   calibration=FILE  the calibration file (see above), relative to the working directory.
//
// Frames: frame i is the i-th depth image, timestamp i / fps. Depth is converted to
// millimetres (value x depth_unit / 0.001, rounded, saturating at 65535; 0 stays "no
// reading"), so SensorInfo.depth_scale_m is 0.001. SensorInfo.frame_count = the number of
// depth images.
//
// Errors of Open, each one line naming the folder and what is wrong: "not_found" (no DIR, no
// DIR/depth, no .png in it, no calibration file, a colour image missing: the first named),
// "usage" (both rgb/ and color/, more than one calibration file, a bad option), "corrupt" (a
// gap in numbered frames: the first missing name; two files with the same number; a depth
// file that is not a 16-bit single-channel PNG; depth images of different sizes; depth whose
// size differs from the calibration's; colour whose size differs from the depth's; the
// calibration file's frame count differs from the depth images'), and the calibration file's
// errors (camera_calibration_file.h). Errors of Next: "corrupt" (an image that does not
// decode or whose size or format changed), "not_found" (an image deleted since Open),
// "no_depth" (frame_checks.h).

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "capture-client/source/frame_checks.h"
#include "capture-client/source/frame_source.h"
#include "capture-client/source/image_undistorter.h"

namespace reenact::capture {

struct RgbdFolderOptions {
  std::optional<std::filesystem::path> calibration;  // nullopt: looked for in DIR
  std::optional<double> depth_unit_m;                // nullopt: the file's, else 0.001
  std::optional<double> fps;                         // nullopt: the file's, else 30
  std::optional<bool> mirrored;                      // nullopt: the file's, else false
  enum class Undistort { kBoth, kColor, kNone };
  Undistort undistort = Undistort::kBoth;
  int max_leading_empty_depth_frames = 30;  // frame_checks.h, >= 1

  void Check() const;  // throws CheckError: depth_unit_m in (0, 1], fps > 0 when set
};

class RgbdFolderSource : public FrameSource {
 public:
  static Expected<std::unique_ptr<RgbdFolderSource>> Open(const std::filesystem::path& dir,
                                                          const RgbdFolderOptions& options);
  // "DIR?calibration=FILE&depth_unit=M&fps=F&mirrored=0|1&undistort=both|color|none".
  static Expected<std::unique_ptr<RgbdFolderSource>> OpenSpec(const std::string& argument);

  const SensorInfo& info() const override { return info_; }
  Expected<std::optional<SensorFrame>> Next() override;

  // The depth images in frame order (paths), the colour images (empty without colour).
  const std::vector<std::filesystem::path>& depth_files() const { return depth_files_; }
  const std::vector<std::filesystem::path>& color_files() const { return color_files_; }
  // The camera as the calibration file gives it (the stored images' camera, before any flip or
  // undistortion), with the images' size.
  const PinholeCamera& file_camera() const { return file_camera_; }
  bool mirrored() const { return mirrored_; }
  const std::filesystem::path& calibration_file() const { return calibration_file_; }

 private:
  RgbdFolderSource() = default;

  std::filesystem::path dir_;
  RgbdFolderOptions options_;
  SensorInfo info_;
  std::filesystem::path calibration_file_;
  PinholeCamera file_camera_;
  bool mirrored_ = false;
  double depth_unit_m_ = 0.001;
  std::vector<std::filesystem::path> depth_files_;
  std::vector<std::filesystem::path> color_files_;
  std::optional<ImageUndistorter> undistorter_;
  DepthPresenceGuard depth_guard_;
  size_t next_ = 0;
};

}  // namespace reenact::capture
