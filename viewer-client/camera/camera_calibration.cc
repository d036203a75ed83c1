#include "viewer-client/camera/camera_calibration.h"

#include <cmath>
#include <opencv2/core.hpp>
#include <string>

namespace reenact::viewer {
namespace {

Error Corrupt(const std::filesystem::path& path, const std::string& what) {
  return MakeError("corrupt", "calibration " + path.string() + ": " + what +
                                  " (see docs/calibration/ for the expected layout)");
}

bool AllFinite(const cv::Mat& m) { return cv::checkRange(m); }

}  // namespace

Expected<PinholeCamera> LoadCameraCalibration(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    return MakeError("not_found", "calibration file " + path.string() + " does not exist");
  }
  cv::FileStorage fs;
  try {
    if (!fs.open(path.string(), cv::FileStorage::READ)) {
      return Corrupt(path, "not an OpenCV YAML or JSON file");
    }
  } catch (const cv::Exception& e) {
    return Corrupt(path, "not an OpenCV YAML or JSON file (" + std::string(e.what()) + ")");
  }
  try {
    PinholeCamera camera;
    const cv::FileNode width = fs["image_width"], height = fs["image_height"];
    if (!width.isInt() || !height.isInt() || static_cast<int>(width) <= 0 ||
        static_cast<int>(height) <= 0) {
      return Corrupt(path, "image_width and image_height must be positive integers");
    }
    camera.width = static_cast<int>(width);
    camera.height = static_cast<int>(height);

    cv::Mat k;
    fs["camera_matrix"] >> k;
    if (k.empty() || k.rows != 3 || k.cols != 3) {
      return Corrupt(path, "camera_matrix must be a 3x3 matrix");
    }
    k.convertTo(k, CV_64F);
    if (!AllFinite(k)) return Corrupt(path, "camera_matrix has a non-finite value");
    const double fx = k.at<double>(0, 0), fy = k.at<double>(1, 1);
    if (!(fx > 0) || !(fy > 0) || k.at<double>(0, 1) != 0 || k.at<double>(1, 0) != 0 ||
        k.at<double>(2, 0) != 0 || k.at<double>(2, 1) != 0 || k.at<double>(2, 2) != 1) {
      return Corrupt(path,
                     "camera_matrix must be [fx 0 cx; 0 fy cy; 0 0 1] with fx, fy > 0 (no skew)");
    }
    camera.fx = fx;
    camera.fy = fy;
    camera.cx = k.at<double>(0, 2);
    camera.cy = k.at<double>(1, 2);

    const cv::FileNode dist_node = fs["distortion_coefficients"];
    if (!dist_node.empty()) {
      cv::Mat d;
      dist_node >> d;
      if (d.empty() || (d.rows != 1 && d.cols != 1)) {
        return Corrupt(path, "distortion_coefficients must be one row or column of numbers");
      }
      d = d.reshape(1, 1);
      d.convertTo(d, CV_64F);
      const int n = d.cols;
      if (n != 4 && n != 5 && n != 8) {
        return Corrupt(
            path, "distortion_coefficients must hold 4, 5 or 8 values, not " + std::to_string(n));
      }
      if (!AllFinite(d)) return Corrupt(path, "distortion_coefficients has a non-finite value");
      for (int i = 5; i < n; ++i) {
        if (d.at<double>(0, i) != 0) {
          return MakeError("unsupported",
                           "calibration " + path.string() +
                               ": the rational distortion terms k4-k6 are not supported; "
                               "calibrate with the 5-coefficient model");
        }
      }
      camera.distortion.k1 = d.at<double>(0, 0);
      camera.distortion.k2 = d.at<double>(0, 1);
      camera.distortion.p1 = d.at<double>(0, 2);
      camera.distortion.p2 = d.at<double>(0, 3);
      if (n >= 5) camera.distortion.k3 = d.at<double>(0, 4);
    }
    return camera;
  } catch (const cv::Exception& e) {
    return Corrupt(path, std::string("unreadable field (") + e.what() + ")");
  }
}

}  // namespace reenact::viewer
