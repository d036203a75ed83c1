#pragma once
// The AR presentation (issue 7): the reenactment composited over the viewer's own camera.
//
// For camera frame i (timestamp t_i):
//  1. the Relocaliser (reloc/relocaliser.h) relocalises or tracks the frame against the clip's
//     map, giving viewer_from_world in the clip's world frame, or "lost";
//  2. the clip's output frame is chosen by the clip clock:
//       kCameraTime (default): k = floor((t_i - t_0) * frame_rate_hz) mod frame_count, so the
//                              reenactment plays at its recorded speed whatever the camera's
//                              frame rate (t_0: the first camera frame's timestamp; a
//                              timestamp earlier than t_0 counts as t_0);
//       kFrameIndex:           k = i mod frame_count (one clip frame per camera frame);
//  3. with a pose, the reenactment of frame k is drawn from that pose with the camera's
//     intrinsics over the camera image (the renderer's background: camera pixels everywhere
//     the subject is not, cylinder fragments over them, depth-tested among themselves). A
//     calibration with lens distortion has its camera image undistorted first (cv::undistort,
//     same K), since the GPU draws an ideal pinhole image; the relocaliser sees the raw frame.
//     Without a pose the output is the camera image alone;
//  4. with draw_status, a banner at the top states the tracking state: green "tracked" /
//     "relocalised" with the inlier count, red "LOST" with what to do.
// The output has the camera's size.

#include <Eigen/Geometry>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/error/expected.h"
#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "proto/clip/map_codec.h"
#include "viewer-client/camera/camera_source.h"
#include "viewer-client/play/reenactment.h"
#include "viewer-client/play/texture_cache.h"
#include "viewer-client/reloc/relocaliser.h"
#include "viewer-client/render/renderer.h"

namespace reenact::viewer {

enum class ClipClock { kCameraTime, kFrameIndex };

// "time", "frames".
std::string_view ClipClockName(ClipClock clock);

struct ArFrameOptions {
  ClipClock clock = ClipClock::kCameraTime;
  bool textured = true;  // false: bare cylinders
  bool draw_skeleton = false;
  bool draw_status = true;  // the state banner (a band of the top 28 rows at most)
  RelocaliserOptions relocaliser;

  void Check() const;
};

struct ArFrame {
  int camera_frame = 0;    // i
  double timestamp_s = 0;  // t_i
  int clip_frame = 0;      // k
  int texture_frame = -1;  // n_bar; -1 when lost or no stored frame fits
  RelocFrameResult reloc;  // state, pose (viewer_from_world), inliers, timing
  RenderedFrame out;       // the composite (camera size) and the subject's mask
  // Wall time of each stage, milliseconds (reloc.ms: relocalising or tracking):
  double select_ms = 0;     // texture selection and the draw list (Reenactment::Build; 0 lost)
  double render_ms = 0;     // drawing over the camera image and read-back (0 when lost)
  double composite_ms = 0;  // the camera image as background (undistortion) and the banner
  double total_ms = 0;      // the whole of Process
  // The camera's true pose where the source knows it (synthetic:), and with a pose the
  // relocalised pose's error against it: camera-centre distance (cm) and rotation angle of
  // R_true^T R_est (degrees).
  std::optional<Eigen::Isometry3d> true_world_from_viewer;
  std::optional<double> err_cm, err_deg;
};

// A camera frame located (ArCompositor::Locate): everything of its ArFrame up to the
// relocaliser's result (camera_frame, timestamp_s, clip_frame, reloc, the truth and its
// errors; total_ms so far) and the camera image to draw over.
struct ArLocatedFrame {
  ArFrame frame;
  ImageRgb8 image;
};

// Turns camera frames into AR frames. Holds the relocaliser's track and the renderer's
// texture cache, so frames must come in camera order.
class ArCompositor {
 public:
  // renderer: a renderer of the camera's size (it stays owned by the caller and must outlive
  // this object, as must reenactment). Errors: "invalid_argument" for a camera that fails
  // Check() or a renderer of another size; "map_too_small" when the clip's map cannot be
  // relocalised against (fewer than options.relocaliser.min_map_points points: the message
  // says how many it has and that the orbit presentation still works).
  static Expected<ArCompositor> Create(const Reenactment& reenactment, proto::ClipMap map,
                                       const PinholeCamera& camera, Renderer& renderer,
                                       const ArFrameOptions& options = {});

  // One camera frame. clip_frame, when given, is the clip frame k to show instead of the clip
  // clock's (an interactive player's own clock: pause, scrub, speed); CheckError unless in
  // [0, frame_count). Errors: "invalid_argument" when its image is empty, not RGB or not of
  // the camera's size (the message gives both sizes: the calibration does not fit the
  // camera), or its timestamp is not finite.
  Expected<ArFrame> Process(const CameraFrame& frame, std::optional<int> clip_frame = {});

  // Process in two steps: Locate (steps 1-2: the checks, the clip clock and the relocaliser;
  // Process's errors) and Compose (steps 3-4: drawing on the renderer; clip_frame as in
  // Process, replacing the clip clock's k). Locate touches only the relocaliser's track and
  // the clock, Compose only the renderer, the texture cache and the selection history, so
  // Locate of camera frame i + 1 may run on another thread while Compose of frame i runs on
  // the renderer's (ar_pipeline.h); each must see its frames in camera order. Locate keeps
  // the frame's image for Compose (moved, not copied, when given an rvalue). Compose's
  // CheckError: a located image of another size than the camera's, clip_frame out of range.
  Expected<ArLocatedFrame> Locate(CameraFrame frame);
  ArFrame Compose(ArLocatedFrame located, std::optional<int> clip_frame = {});

  // The presentation toggles of the frames to come (ArFrameOptions' textured, draw_skeleton).
  void SetPresentation(bool textured, bool draw_skeleton);

  const PinholeCamera& camera() const { return camera_; }
  // The camera the renderer draws with: camera() without distortion.
  const PinholeCamera& render_camera() const { return render_camera_; }

  ArCompositor(ArCompositor&&) = default;
  ArCompositor& operator=(ArCompositor&&) = delete;

 private:
  ArCompositor(const Reenactment& reenactment, Relocaliser relocaliser, const PinholeCamera& camera,
               Renderer& renderer, const ArFrameOptions& options);

  const Reenactment& reenactment_;
  Relocaliser relocaliser_;
  PinholeCamera camera_, render_camera_;
  Renderer& renderer_;
  ArFrameOptions options_;
  TextureCache textures_;
  PartSelectionHistory selection_history_;  // per-part selection across output frames
  int frames_ = 0;
  std::optional<double> first_timestamp_s_;
};

// Draws the state banner onto an RGB image in place (draw_status above).
void DrawArStatus(const RelocFrameResult& reloc, ImageRgb8& image);

struct ArPlayOptions {
  std::filesystem::path out_dir;  // created if missing
  int max_frames = -1;            // camera frames to process; -1 = until the camera ends
  ArFrameOptions frame;
  int contact_sheet_columns = 6;  // >= 1
  int contact_sheet_thumb_width = 213;
  bool write_mp4 = true;     // at the clip's frame rate
  bool write_masks = false;  // frames/mask_NNNN.png: 255 where the subject was drawn

  void Check() const;
};

struct ArPlaySummary {
  int frames = 0;
  int relocalised = 0, tracked = 0, lost = 0;
  double reloc_ms_median = 0;   // Relocaliser::ProcessFrame
  double render_ms_median = 0;  // over posed frames
  // Against the truth, when the camera knows it (truth_frames > 0): frames within 2 cm and 1
  // degree (a lost frame counts as outside), and median errors over posed frames.
  int truth_frames = 0, within_2cm_1deg = 0;
  double median_err_cm = 0, median_err_deg = 0;
  double seconds = 0;           // wall time including file output
  std::string mp4_path;         // empty if no video was written
  std::string mp4_warning;      // why not, if so
};

// Adds frames up into an ArPlaySummary: the state counts, the medians, the truth figures
// (seconds and the MP4 fields are the caller's).
class ArSummaryBuilder {
 public:
  void Add(const ArFrame& frame);
  ArPlaySummary summary() const;
  int frames() const { return counts_.frames; }

 private:
  ArPlaySummary counts_;
  std::vector<double> reloc_ms_, render_ms_, err_cm_, err_deg_;
};

// The headless AR play: every camera frame through ArCompositor, written under out_dir as the
// orbit presentation writes (headless_player.h): frames/frame_NNNN.png, contact_sheet.png,
// reenactment.mp4, render.json with "presentation": "ar", the camera's intrinsics, the clip
// clock, and per frame the camera frame's timestamp, clip frame k, texture frame n_bar, state
// ("relocalised" / "tracked" / "lost"), features, matches, inliers, reloc_ms, the lost reason
// and world_from_viewer (row-major 4x4, or null when lost); with a camera that knows its true
// pose also true_world_from_viewer, err_cm and err_deg per frame (null when lost) and a
// "truth" object with frames, within_2cm_1deg, median_err_cm and median_err_deg.
// Errors: those of ArCompositor::Create and Process, of the camera ("empty" when it delivers
// no frame at all), of the renderer and of writing files.
Expected<ArPlaySummary> PlayArHeadless(const Reenactment& reenactment, proto::ClipMap map,
                                       CameraSource& camera, const std::string& clip_id,
                                       const ArPlayOptions& options);

}  // namespace reenact::viewer
