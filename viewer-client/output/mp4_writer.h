#pragma once
// MP4 video of rendered frames through OpenCV's VideoWriter: H.264 ('avc1') when the
// OpenCV build can encode it, else MPEG-4 Part 2 ('mp4v').

#include <memory>
#include <string>
#include <vector>

#include "common/error/expected.h"
#include "common/image/image.h"

namespace reenact::viewer {

// Move-only. Frames must all have the size given to Open.
class Mp4Writer {
 public:
  // Opens `path` for width x height frames at fps frames per second. Errors:
  // "invalid_argument" for a non-positive size or fps; "io" when neither codec can open the
  // file (missing folder, no encoder); the message names the path.
  static Expected<Mp4Writer> Open(const std::string& path, int width, int height, double fps);

  Mp4Writer(Mp4Writer&&) noexcept;
  Mp4Writer& operator=(Mp4Writer&&) noexcept;
  ~Mp4Writer();  // closes the file

  // Appends one RGB frame (converted to BGR for OpenCV). Errors: "invalid_argument" for a
  // frame that is not RGB of the opened size, "io" if the writer is closed.
  Status Write(const ImageRgb8& frame);
  // Finishes the file; later writes fail. Idempotent.
  void Close();

  int frames_written() const;
  // "avc1" or "mp4v": the codec that opened.
  const std::string& codec() const;
  const std::string& path() const;

 private:
  struct State;
  explicit Mp4Writer(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

// Writes `frames` (RGB, width x height) to a new MP4 at `path`, fps frames per second, and sets
// *written_path to it. Where the file cannot be opened (no encoder) the video is skipped
// instead: *warning says why. Errors: those of Write.
Status WriteMp4(const std::vector<ImageRgb8>& frames, const std::string& path, int width,
                int height, double fps, std::string* written_path, std::string* warning);

}  // namespace reenact::viewer
