#include "viewer-client/camera/tum_directory_source.h"

#include <cmath>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

namespace reenact::viewer {
namespace {

Expected<std::vector<TumColorFrame>> ReadList(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) return MakeError("not_found", "cannot read " + file.string());
  std::vector<TumColorFrame> frames;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    std::string time_text, name;
    if (!(fields >> time_text >> name)) {
      return MakeError("corrupt", file.string() + " line " + std::to_string(number) +
                                      ": expected 'timestamp filename'");
    }
    double t = 0;
    try {
      size_t used = 0;
      t = std::stod(time_text, &used);
      if (used != time_text.size()) throw std::invalid_argument("trailing characters");
    } catch (const std::exception&) {
      t = NAN;
    }
    if (!std::isfinite(t)) {
      return MakeError("corrupt", file.string() + " line " + std::to_string(number) +
                                      ": timestamp '" + time_text + "' is not a finite number");
    }
    if (!frames.empty() && !(t > frames.back().timestamp_s)) {
      return MakeError("corrupt", file.string() + " line " + std::to_string(number) +
                                      ": timestamps must increase strictly");
    }
    frames.push_back({t, name});
  }
  if (frames.empty()) return MakeError("empty", file.string() + " lists no frame");
  return frames;
}

class TumDirectorySource : public CameraSource {
 public:
  TumDirectorySource(std::filesystem::path dir, std::vector<TumColorFrame> frames,
                     const PinholeCamera& camera)
      : dir_(std::move(dir)), frames_(std::move(frames)), camera_(camera) {}

  std::string description() const override { return "tum:" + dir_.string(); }
  const PinholeCamera& camera() const override { return camera_; }

  Expected<std::optional<CameraFrame>> Next() override {
    if (next_ >= frames_.size()) return std::optional<CameraFrame>();
    const TumColorFrame& f = frames_[next_++];
    const std::filesystem::path file = dir_ / f.file;
    cv::Mat bgr = cv::imread(file.string(), cv::IMREAD_COLOR);
    if (bgr.empty()) {
      return MakeError("corrupt", "cannot read or decode the colour image " + file.string());
    }
    if (bgr.cols != camera_.width || bgr.rows != camera_.height) {
      return MakeError("invalid_argument",
                       file.string() + " is " + std::to_string(bgr.cols) + "x" +
                           std::to_string(bgr.rows) + " but the calibration is for " +
                           std::to_string(camera_.width) + "x" + std::to_string(camera_.height));
    }
    CameraFrame out;
    out.timestamp_s = f.timestamp_s;
    out.color = ImageRgb8(bgr.cols, bgr.rows, 3);
    cv::Mat rgb(bgr.rows, bgr.cols, CV_8UC3, out.color.data.data());
    cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
    return std::optional<CameraFrame>(std::move(out));
  }

 private:
  std::filesystem::path dir_;
  std::vector<TumColorFrame> frames_;
  PinholeCamera camera_;
  size_t next_ = 0;
};

}  // namespace

Expected<std::vector<TumColorFrame>> ReadTumColorFrames(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) {
    return MakeError("not_found", "TUM directory " + dir.string() + " does not exist");
  }
  if (std::filesystem::exists(dir / "rgb.txt", ec)) return ReadList(dir / "rgb.txt");
  if (std::filesystem::exists(dir / "associations.txt", ec)) {
    return ReadList(dir / "associations.txt");
  }
  return MakeError("not_found", dir.string() +
                                    " has neither rgb.txt nor associations.txt: not a TUM RGB-D "
                                    "sequence directory");
}

Expected<std::unique_ptr<CameraSource>> OpenTumDirectorySource(const std::filesystem::path& dir,
                                                               const PinholeCamera& camera) {
  auto frames = ReadTumColorFrames(dir);
  if (!frames.ok()) return frames.error();
  return std::unique_ptr<CameraSource>(
      std::make_unique<TumDirectorySource>(dir, std::move(*frames), camera));
}

}  // namespace reenact::viewer
