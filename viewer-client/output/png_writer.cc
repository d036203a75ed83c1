#include "viewer-client/output/png_writer.h"

#include <opencv2/imgcodecs.hpp>

#include "viewer-client/output/cv_image.h"

namespace reenact::viewer {

Status WritePng(const std::string& path, const ImageRgb8& image) {
  if (image.empty() || (image.channels != 1 && image.channels != 3)) {
    return MakeError("invalid_argument",
                     "cannot write " + path + ": the image is empty or not grey/RGB");
  }
  try {
    if (!cv::imwrite(path, ToBgrMat(image))) {
      return MakeError("io", "cannot write PNG " + path + " (does the folder exist?)");
    }
  } catch (const cv::Exception& e) {
    return MakeError("io", "cannot write PNG " + path + ": " + e.what());
  }
  return {};
}

}  // namespace reenact::viewer
