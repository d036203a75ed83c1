#pragma once
// Plays a reenactment without a window: renders every output frame through EGL surfaceless
// OpenGL from the orbit camera and writes, under out_dir:
//   frames/frame_NNNN.png   each output frame
//   contact_sheet.png       a grid of thumbnails
//   frames/mask_NNNN.png    with write_masks: the rendered subject's silhouette
//   reenactment.mp4         the frames as a video (skipped with a warning if no encoder)
//   render.json             per frame: clip frame k, chosen texture frame n_bar, the viewer
//                           camera (intrinsics, world_from_viewer), so that evaluations can
//                           render the ground truth from the very same viewpoint

#include <filesystem>
#include <string>

#include "common/error/expected.h"
#include "viewer-client/play/orbit_camera.h"
#include "viewer-client/play/reenactment.h"

namespace reenact::viewer {

struct HeadlessPlayOptions {
  std::filesystem::path out_dir;  // created if missing
  int max_frames = -1;            // -1 = the whole clip, else >= 1
  int width = 640;                // output size, pixels, >= 16
  int height = 480;
  OrbitCameraOptions orbit;
  bool textured = true;           // false: bare cylinders
  bool draw_skeleton = false;
  int contact_sheet_columns = 6;  // >= 1
  int contact_sheet_thumb_width = 213;
  bool write_mp4 = true;
  bool write_masks = false;       // frames/mask_NNNN.png: 255 where the subject was drawn

  void Check() const;
};

struct PlaySummary {
  int frames = 0;
  double render_fps = 0;          // rendering + read-back only, median over frames
  double seconds = 0;             // wall time including file output
  std::string mp4_path;           // empty if no video was written
  std::string mp4_warning;        // why not, if so
  std::string clip_id;
};

Expected<PlaySummary> PlayHeadless(const Reenactment& reenactment, const std::string& clip_id,
                                   const HeadlessPlayOptions& options);

}  // namespace reenact::viewer
