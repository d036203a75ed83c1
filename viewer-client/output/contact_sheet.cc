#include "viewer-client/output/contact_sheet.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <opencv2/imgproc.hpp>

#include "viewer-client/output/cv_image.h"

namespace reenact::viewer {

ImageRgb8 MakeContactSheet(const std::vector<ImageRgb8>& frames, int columns, int thumb_width,
                           const std::vector<int>& frame_numbers) {
  REENACT_CHECK(!frames.empty(), "a contact sheet needs at least one frame");
  REENACT_CHECK(columns >= 1 && thumb_width >= 1, "columns and thumbnail width must be >= 1");
  REENACT_CHECK(frame_numbers.empty() || frame_numbers.size() == frames.size(),
                "frame_numbers must be empty or one per frame");
  const ImageRgb8& first = frames.front();
  for (const ImageRgb8& f : frames) {
    REENACT_CHECK(!f.empty() && f.channels == 3 && f.width == first.width &&
                      f.height == first.height,
                  "contact sheet frames must be non-empty RGB images of one size");
  }
  const int count = static_cast<int>(frames.size());
  const int thumb_height = std::max(
      1, static_cast<int>(std::lround(static_cast<double>(first.height) * thumb_width /
                                      first.width)));
  const int cols = std::min(columns, count);
  const int rows = (count + cols - 1) / cols;
  const int gap = kContactSheetGap;
  const cv::Scalar background(kContactSheetBackground[2], kContactSheetBackground[1],
                              kContactSheetBackground[0]);
  cv::Mat sheet(rows * thumb_height + (rows + 1) * gap, cols * thumb_width + (cols + 1) * gap,
                CV_8UC3, background);

  const double font_scale = std::clamp(thumb_height / 160.0, 0.3, 1.0);
  const int thickness = font_scale > 0.6 ? 2 : 1;
  for (int i = 0; i < count; ++i) {
    const cv::Rect cell(gap + (i % cols) * (thumb_width + gap),
                        gap + (i / cols) * (thumb_height + gap), thumb_width, thumb_height);
    cv::Mat thumb;
    cv::resize(ToBgrMat(frames[static_cast<size_t>(i)]), thumb, cell.size(), 0, 0,
               cv::INTER_AREA);
    thumb.copyTo(sheet(cell));

    const std::string label =
        std::to_string(frame_numbers.empty() ? i : frame_numbers[static_cast<size_t>(i)]);
    int baseline = 0;
    const cv::Size text =
        cv::getTextSize(label, cv::FONT_HERSHEY_SIMPLEX, font_scale, thickness, &baseline);
    const cv::Rect box = cv::Rect(cell.x, cell.y, text.width + 6, text.height + baseline + 6) & cell;
    cv::Mat roi = sheet(cell);
    cv::rectangle(sheet, box, cv::Scalar(0, 0, 0), cv::FILLED);
    cv::putText(roi, label, cv::Point(3, 3 + text.height), cv::FONT_HERSHEY_SIMPLEX, font_scale,
                cv::Scalar(255, 255, 255), thickness, cv::LINE_AA);
  }
  return FromBgrMat(sheet);
}

}  // namespace reenact::viewer
