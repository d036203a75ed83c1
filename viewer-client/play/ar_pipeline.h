#pragma once
// The AR loop on two cores: camera frame i + 1 is read and located (ArCompositor::Locate: the
// relocaliser, about as long as drawing on a 2-core machine) on a worker thread while frame i
// is composed (ArCompositor::Compose: selection and drawing) on the caller's thread, the one
// that owns the renderer's GL context. The frames come out in camera order and each is what
// ArCompositor::Process would make of it. The throughput approaches that of the slower step
// instead of the sum of both; a frame's own time from its reading to its output grows where
// the two steps compete for the cores (llvmpipe draws on both: on 2 cores the whole AR loop
// runs at 30-33 fps pipelined against 24 step after step, a frame's time about 50 ms against
// 40; reenact-bench viewer).
//
// Threads: the worker runs `next` and Locate, one call at a time and never beside another
// Locate; Compose runs on the caller's thread inside Next(). The compositor's presentation
// toggles (SetPresentation) may be changed between calls to Next() on the caller's thread.

#include <functional>
#include <future>
#include <optional>

#include "common/error/expected.h"
#include "viewer-client/camera/camera_source.h"
#include "viewer-client/play/ar_player.h"

namespace reenact::viewer {

class ArPipeline {
 public:
  // The next camera frame, std::nullopt at the end (CameraSource::Next's contract).
  using FrameSource = std::function<Expected<std::optional<CameraFrame>>()>;

  // compositor and whatever next reads must outlive this object. Starts reading and locating
  // the first frame at once.
  ArPipeline(ArCompositor& compositor, FrameSource next);
  // Waits for the worker's call in flight, if any.
  ~ArPipeline();
  ArPipeline(const ArPipeline&) = delete;
  ArPipeline& operator=(const ArPipeline&) = delete;

  // The next AR frame (composed with clip_frame as ArCompositor::Compose takes it), after
  // starting to read and locate the one after it; std::nullopt at the camera's end. Errors:
  // the camera's and Locate's, for the frame they concern; after the end or an error, every
  // further call returns the same without reading the camera again.
  Expected<std::optional<ArFrame>> Next(std::optional<int> clip_frame = {});

 private:
  using Located = Expected<std::optional<ArLocatedFrame>>;
  std::future<Located> ReadAndLocate();

  ArCompositor& compositor_;
  FrameSource next_;
  std::future<Located> pending_;
  std::optional<Error> error_;
  bool ended_ = false;
};

// The frames of a camera, at most max_frames of them (-1: until it ends); camera must outlive
// the source.
ArPipeline::FrameSource CameraFrames(CameraSource& camera, int max_frames);

}  // namespace reenact::viewer
