#include "viewer-client/camera/video_capture_source.h"

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <string>

namespace reenact::viewer {
namespace {

class VideoCaptureSource : public CameraSource {
 public:
  VideoCaptureSource(std::string description, cv::VideoCapture capture, cv::Mat first,
                     const PinholeCamera& camera)
      : description_(std::move(description)),
        capture_(std::move(capture)),
        pending_(std::move(first)),
        camera_(camera) {}

  std::string description() const override { return description_; }
  const PinholeCamera& camera() const override { return camera_; }

  Expected<std::optional<CameraFrame>> Next() override {
    cv::Mat bgr;
    double t = 0;
    if (!pending_.empty()) {
      bgr = std::move(pending_);
      pending_ = cv::Mat();
      t = first_time_s_;
    } else {
      if (!capture_.read(bgr) || bgr.empty()) return std::optional<CameraFrame>();
      t = capture_.get(cv::CAP_PROP_POS_MSEC) * 1e-3;
    }
    if (bgr.cols != camera_.width || bgr.rows != camera_.height) {
      return MakeError("invalid_argument",
                       description_ + " delivers " + std::to_string(bgr.cols) + "x" +
                           std::to_string(bgr.rows) + " frames but the calibration is for " +
                           std::to_string(camera_.width) + "x" + std::to_string(camera_.height));
    }
    CameraFrame out;
    out.timestamp_s = t;
    out.color = ImageRgb8(bgr.cols, bgr.rows, 3);
    cv::Mat rgb(bgr.rows, bgr.cols, CV_8UC3, out.color.data.data());
    if (bgr.type() == CV_8UC3) {
      cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
    } else if (bgr.type() == CV_8UC1) {
      cv::cvtColor(bgr, rgb, cv::COLOR_GRAY2RGB);
    } else {
      return MakeError("unsupported", description_ + " delivers frames of OpenCV type " +
                                          std::to_string(bgr.type()) + ", not 8-bit colour");
    }
    return std::optional<CameraFrame>(std::move(out));
  }

  double first_time_s_ = 0;

 private:
  std::string description_;
  cv::VideoCapture capture_;
  cv::Mat pending_;  // the first frame, read at open to prove the source delivers
  PinholeCamera camera_;
};

}  // namespace

Expected<std::unique_ptr<CameraSource>> OpenVideoFileSource(const std::filesystem::path& file,
                                                            const PinholeCamera& camera) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    return MakeError("not_found", "video file " + file.string() + " does not exist");
  }
  cv::VideoCapture capture(file.string(), cv::CAP_FFMPEG);
  if (!capture.isOpened()) {
    return MakeError("unsupported",
                     "cannot decode the video " + file.string() + " (not a video FFmpeg reads)");
  }
  cv::Mat first;
  if (!capture.read(first) || first.empty()) {
    return MakeError("unsupported", "the video " + file.string() + " has no readable frame");
  }
  const double t = capture.get(cv::CAP_PROP_POS_MSEC) * 1e-3;
  auto source = std::make_unique<VideoCaptureSource>("video:" + file.string(), std::move(capture),
                                                     std::move(first), camera);
  source->first_time_s_ = t;
  return std::unique_ptr<CameraSource>(std::move(source));
}

Expected<std::unique_ptr<CameraSource>> OpenLiveCameraSource(int index,
                                                             const PinholeCamera& camera) {
  const std::string name = "live:" + std::to_string(index);
  if (index < 0) return MakeError("usage", "camera index must be >= 0, not " + name);
  cv::VideoCapture capture;
  try {
    capture.open(index);
  } catch (const cv::Exception&) {
  }
  if (!capture.isOpened()) {
    return MakeError("unavailable", "no camera " + std::to_string(index) +
                                        " can be opened (none attached, or no permission for "
                                        "/dev/video" +
                                        std::to_string(index) + ")");
  }
  capture.set(cv::CAP_PROP_FRAME_WIDTH, camera.width);
  capture.set(cv::CAP_PROP_FRAME_HEIGHT, camera.height);
  cv::Mat first;
  if (!capture.read(first) || first.empty()) {
    return MakeError("unavailable", "camera " + std::to_string(index) + " delivers no frames");
  }
  return std::unique_ptr<CameraSource>(
      std::make_unique<VideoCaptureSource>(name, std::move(capture), std::move(first), camera));
}

}  // namespace reenact::viewer
