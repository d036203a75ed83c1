#include "viewer-client/output/mp4_writer.h"

#include <cmath>
#include <opencv2/videoio.hpp>

#include "viewer-client/output/cv_image.h"

namespace reenact::viewer {

struct Mp4Writer::State {
  cv::VideoWriter writer;
  std::string path;
  std::string codec;
  int width = 0, height = 0;
  int frames = 0;
};

Mp4Writer::Mp4Writer(std::unique_ptr<State> state) : state_(std::move(state)) {}
Mp4Writer::Mp4Writer(Mp4Writer&&) noexcept = default;
Mp4Writer& Mp4Writer::operator=(Mp4Writer&&) noexcept = default;
Mp4Writer::~Mp4Writer() {
  if (state_) Close();
}

Expected<Mp4Writer> Mp4Writer::Open(const std::string& path, int width, int height, double fps) {
  if (width <= 0 || height <= 0 || !(fps > 0) || !std::isfinite(fps)) {
    return MakeError("invalid_argument",
                     "cannot open video " + path + ": size and frame rate must be positive");
  }
  auto state = std::make_unique<State>();
  state->path = path;
  state->width = width;
  state->height = height;
  for (const char* codec : {"avc1", "mp4v"}) {
    try {
      const int fourcc = cv::VideoWriter::fourcc(codec[0], codec[1], codec[2], codec[3]);
      if (state->writer.open(path, cv::CAP_FFMPEG, fourcc, fps, cv::Size(width, height), true)) {
        state->codec = codec;
        return Mp4Writer(std::move(state));
      }
    } catch (const cv::Exception&) {
      // An encoder that throws counts as unavailable; try the next one.
    }
  }
  return MakeError("io", "cannot open video " + path +
                             " for writing with avc1 or mp4v (does the folder exist? is "
                             "OpenCV built with FFmpeg?)");
}

Status Mp4Writer::Write(const ImageRgb8& frame) {
  if (!state_->writer.isOpened()) {
    return MakeError("io", "video " + state_->path + " is already closed");
  }
  if (frame.channels != 3 || frame.width != state_->width || frame.height != state_->height) {
    return MakeError("invalid_argument",
                     "video " + state_->path + " takes RGB frames of " +
                         std::to_string(state_->width) + "x" + std::to_string(state_->height) +
                         ", got " + std::to_string(frame.width) + "x" +
                         std::to_string(frame.height) + "x" + std::to_string(frame.channels));
  }
  state_->writer.write(ToBgrMat(frame));
  ++state_->frames;
  return {};
}

void Mp4Writer::Close() {
  if (state_->writer.isOpened()) state_->writer.release();
}

int Mp4Writer::frames_written() const { return state_->frames; }
const std::string& Mp4Writer::codec() const { return state_->codec; }
const std::string& Mp4Writer::path() const { return state_->path; }

Status WriteMp4(const std::vector<ImageRgb8>& frames, const std::string& path, int width,
                int height, double fps, std::string* written_path, std::string* warning) {
  auto writer = Mp4Writer::Open(path, width, height, fps);
  if (!writer.ok()) {
    *warning = writer.error().message;
    return {};
  }
  for (const ImageRgb8& f : frames)
    if (Status s = writer->Write(f); !s.ok()) return s.error();
  writer->Close();
  *written_path = path;
  return {};
}

}  // namespace reenact::viewer
