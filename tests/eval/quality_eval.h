#pragma once
// `reenact-eval quality`: capture a synthetic scenario through the real recording pipeline,
// reenact every frame_step-th frame from orbit viewpoints turned by each angle about the
// subject's vertical axis, render the ground truth from the very same camera, and compare
// (image_metrics.h). Methods: "thesis" (Eq. 5 selection, one stored frame for the whole body,
// Eq. 6-16 mapping). Further methods arrive with the image-quality work.

#include <string>
#include <vector>

#include "common/error/expected.h"

namespace reenact::eval {

struct QualityOptions {
  std::string scenario = "turn-and-kick";
  std::vector<std::string> methods = {"thesis"};
  std::vector<double> views_deg = {0, 30, 60, 90, 135, 180};
  int frame_step = 10;  // >= 1
  int width = 640;      // >= 16
  int height = 480;

  void Check() const;
};

struct QualityRow {
  std::string method;
  std::string scenario;
  double view_deg = 0;
  int n = 0;               // frames compared
  double psnr_db = 0;      // mean over frames with finite PSNR
  double ssim = 0;
  double iou = 0;
  double colour_mae = 0;   // 0..255
  double ms_per_frame = 0; // median: selection + mapping + GL draw + read-back
};

std::vector<std::string> QualityMethods();

Expected<std::vector<QualityRow>> RunQuality(const QualityOptions& options);

}  // namespace reenact::eval
