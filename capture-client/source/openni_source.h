#pragma once
// FrameSource over OpenNI2: a recording (oni:FILE) or a live device (openni[:URI]), through
// the same reading code.
//
// Playback of a recording yields every frame in order: the device's PlaybackControl is set
// to manual speed (-1: the reader advances only when a frame is read, never skipping) before
// the streams start, and to repeat where the recording holds exactly the frames it declares
// (reading ends at those counts; see Teardown); seek() is never used (it crashes Debian's
// reader).
// Before OpenNI2 sees the file, ScanOniFile checks its structure (oni_file_scan.h), so a
// header-only or truncated file fails with a precise error instead of OpenNI2's silent
// refusal. Every wait for a frame is bounded (wait_timeout_ms): a recording that yields no
// frame (OpenNI2 2.2 yields none from a recording without the cropping property) or a
// device that stops sending fails with an Error instead of hanging.
//
// Pairing: colour and depth arrive as separate streams; the oldest colour and depth frames
// are paired when their timestamps differ by at most max_pair_gap_s (default half a frame
// period); otherwise the older of the two has no partner and is dropped. The pair's
// timestamp is the colour frame's (OpenNI microseconds, in seconds).
//
// Registration: depth must be registered to the colour camera (one pixel grid). A live
// device is switched to depth-to-colour registration (an Error if it cannot). A recording
// must say so: OpenNI 1.x recordings store the depth node's AlternativeViewPoint (1 =
// registered); OpenNI2 recordings the device's image-registration mode; `registered=1`
// asserts it for a recording that says neither.
//
// Images: depth in millimetres (DEPTH_1_MM as is, DEPTH_100_UM rounded to mm); colour
// converted to RGB from RGB888, YUV422 (UYVY), YUYV, GRAY8 or JPEG. Cropped frames are placed
// back into their full frame (zeros elsewhere). Mirrored streams (OpenNI 1.x recorded
// Kinect data mirrored by default, and a device may refuse to switch mirroring off) are
// flipped back, so that images follow the OpenCV camera model (x right, y down).
//
// Teardown stops the streams, destroys them, then closes the device. OpenNI2's recording
// player walks its stream list on its own thread without a lock once it has played to the
// end, so destroying a stream then can crash it, and no order of the public calls avoids it
// (docs/decisions.md, Capture). Set to repeat, the player instead waits at the recording's
// start for a read that never comes; a recording that declares other counts than it holds
// keeps the rare risk.
//
// Intrinsics from the field of view (OpenNI2 reports it per stream, in radians):
//   fx = W / (2 tan(hfov / 2)),  fy = H / (2 tan(vfov / 2)),
//   cx = (W - 1) / 2,            cy = (H - 1) / 2,            no distortion.
// (cx, cy) is the centre of the pixel grid in our convention (pixel centres at integers);
// OpenNI's own CoordinateConverter uses W/2, H/2, half a pixel off, within the accuracy of a
// nominal field of view, and the centre stays the centre when a mirrored image is flipped.
// The colour stream's field of view is used; where a recording stores none (OpenNI 1.x
// Kinect recordings store it for the depth node only) the depth stream's is, which for a
// Kinect is the infrared camera's (58.1 x 45.3 deg, fx ~ 576 px at 640) rather than the colour
// camera's that registered depth shares (~62.7 x 48.6 deg, fx ~ 525 px): `fov=62.7x48.6`
// overrides it with the user's value (degrees, horizontal x vertical).
// SensorInfo.description says which field of view was used.

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "capture-client/source/frame_source.h"

namespace reenact::capture {

struct OpenNiSourceOptions {
  int wait_timeout_ms = 2000;               // longest wait for any frame, > 0
  double max_pair_gap_s = 0;                // >= 0; 0 = half the colour stream's frame period
  int max_leading_empty_depth_frames = 30;  // frame_checks.h, >= 1
  // Field of view (degrees, horizontal and vertical, each in (0, 180)) overriding the
  // streams' own.
  std::optional<std::pair<double, double>> fov_deg;
  bool assume_registered = false;  // recordings only: see "Registration" above

  void Check() const;
};

// The pinhole camera of the formulas above. Preconditions (CHECK): width, height > 0 and
// both angles in (0, pi) radians.
PinholeCamera CameraFromFieldOfView(int width, int height, double hfov_rad, double vfov_rad);

class OpenNiSource : public FrameSource {
 public:
  // oni:FILE. Errors: those of ScanOniFile; "unsupported" (no colour or no depth stream,
  // depth not registered, a pixel format or frame size this reader does not handle);
  // "corrupt" (colour and depth sizes differ); "openni" (OpenNI2 refuses the file).
  static Expected<std::unique_ptr<FrameSource>> OpenFile(const std::filesystem::path& file,
                                                         const OpenNiSourceOptions& options);
  // openni[:URI]; an empty URI opens the first device. Errors: "not_found" ("no OpenNI2
  // device found ..." or no device with that URI, listing the connected ones),
  // "unsupported", "openni" (the device refuses to open or start).
  static Expected<std::unique_ptr<FrameSource>> OpenDevice(const std::string& uri,
                                                           const OpenNiSourceOptions& options);

  // Parses the spec arguments "FILE?fov=HxV&registered=1&timeout_ms=N" (oni:) and
  // "URI?fov=HxV&timeout_ms=N" (openni:) and opens the source.
  static Expected<std::unique_ptr<FrameSource>> OpenFileSpec(const std::string& argument);
  static Expected<std::unique_ptr<FrameSource>> OpenDeviceSpec(const std::string& argument);

  ~OpenNiSource() override;
  const SensorInfo& info() const override;
  // Errors: "timeout" (no frame within wait_timeout_ms: see above), "corrupt",
  // "no_depth" (frame_checks.h), "openni" (a read fails).
  Expected<std::optional<SensorFrame>> Next() override;

  struct Impl;

 private:
  explicit OpenNiSource(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace reenact::capture
