#pragma once
// The AR presentation in a GLFW window (render/window.h): every camera frame goes through the
// same ArCompositor as the headless AR play (ar_player.h: relocalise or track, select, draw
// over the camera image, status banner), and the composite is shown in the window, letterboxed.
//
// Camera frames of a file or sequence (tum:, video:, synthetic:) are shown at their own pace:
// frame i no earlier than (t_i - t_0) seconds after the first (never faster than recorded;
// later when processing cannot keep up); a live camera paces itself. The window closes when the
// camera ends, after max_frames frames, or on Escape / q / the close button.
//
// The clip plays on the window's own clock (playback_state.h): space pauses the reenactment
// (the camera keeps running), left/right step one clip frame, +/- change its speed, s toggles
// the skeleton, c bare cylinders, t the texture. Mouse drag and wheel do nothing here: the
// viewpoint is the camera's.

#include "common/error/expected.h"
#include "proto/clip/map_codec.h"
#include "viewer-client/camera/camera_source.h"
#include "viewer-client/play/ar_player.h"
#include "viewer-client/play/reenactment.h"

namespace reenact::viewer {

struct ArWindowOptions {
  int max_frames = -1;      // camera frames to show; -1 = until the camera ends, else >= 1
  ArFrameOptions frame;     // textured and draw_skeleton: the initial state of the toggles
  int window_width = 1280;  // initial window size in screen units, > 0
  int window_height = 720;
  std::string title = "reenact AR";

  void Check() const;
};

// What the window showed: frames, relocalised / tracked / lost counts, stage medians and the
// error against the truth where the camera knows it (as ArPlaySummary; no files, so mp4_path,
// mp4_warning are empty).
//
// Errors: "no_display" (Window::Create's, the message suggesting --headless), those
// of ArCompositor::Create and Process, of the camera ("empty" when it delivers no frame at all).
Expected<ArPlaySummary> PlayArInWindow(const Reenactment& reenactment, proto::ClipMap map,
                                       CameraSource& camera, const ArWindowOptions& options);

}  // namespace reenact::viewer
