#pragma once
// Plays a reenactment in a GLFW window with the free orbit camera: space play/pause,
// left/right scrub, +/- speed, s skeleton, c bare cylinders, t texture, mouse drag orbits,
// wheel zooms, Esc quits. Fails with a clear Error where no display is available.

#include "common/error/expected.h"
#include "viewer-client/play/headless_player.h"
#include "viewer-client/play/reenactment.h"

namespace reenact::viewer {

// Uses options' size, orbit, textured and draw_skeleton as the initial state.
Status PlayInWindow(const Reenactment& reenactment, const HeadlessPlayOptions& options);

}  // namespace reenact::viewer
