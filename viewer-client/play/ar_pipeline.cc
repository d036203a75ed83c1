#include "viewer-client/play/ar_pipeline.h"

#include <utility>

namespace reenact::viewer {

ArPipeline::ArPipeline(ArCompositor& compositor, FrameSource next)
    : compositor_(compositor), next_(std::move(next)), pending_(ReadAndLocate()) {}

ArPipeline::~ArPipeline() {
  if (pending_.valid()) pending_.wait();
}

std::future<ArPipeline::Located> ArPipeline::ReadAndLocate() {
  return std::async(std::launch::async, [this]() -> Located {
    auto frame = next_();
    if (!frame.ok()) return frame.error();
    if (!frame->has_value()) return std::optional<ArLocatedFrame>{};
    auto located = compositor_.Locate(std::move(**frame));
    if (!located.ok()) return located.error();
    return std::optional<ArLocatedFrame>(std::move(located).value());
  });
}

Expected<std::optional<ArFrame>> ArPipeline::Next(std::optional<int> clip_frame) {
  if (error_) return *error_;
  if (ended_) return std::optional<ArFrame>{};
  Located located = pending_.get();
  if (!located.ok()) {
    error_ = located.error();
    return *error_;
  }
  if (!located->has_value()) {
    ended_ = true;
    return std::optional<ArFrame>{};
  }
  pending_ = ReadAndLocate();
  return std::optional<ArFrame>(compositor_.Compose(std::move(**located), clip_frame));
}

ArPipeline::FrameSource CameraFrames(CameraSource& camera, int max_frames) {
  return [&camera, max_frames, read = 0]() mutable -> Expected<std::optional<CameraFrame>> {
    if (max_frames >= 0 && read >= max_frames) return std::optional<CameraFrame>{};
    ++read;
    return camera.Next();
  };
}

}  // namespace reenact::viewer
