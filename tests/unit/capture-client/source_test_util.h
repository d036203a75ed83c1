#pragma once
// Helpers of the frame-source tests: temporary directories, the shared real data, and small
// TUM RGB-D sequences written from constructed images.

#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "tests/support/temp_dir.h"

namespace reenact::capture::testing {

using reenact::test_support::TempDir;

namespace fs = std::filesystem;

inline fs::path SharedData(const std::string& relative) {
  return fs::path(REENACT_SHARED_DATA_DIR) / relative;
}

inline void WriteText(const fs::path& file, const std::string& text) {
  std::ofstream(file) << text;
}

// First `bytes` bytes of `from` written to `to`.
inline void WritePrefix(const fs::path& from, const fs::path& to, size_t bytes) {
  std::ifstream in(from, std::ios::binary);
  std::vector<char> data(bytes);
  in.read(data.data(), static_cast<std::streamsize>(bytes));
  std::ofstream(to, std::ios::binary).write(data.data(), in.gcount());
}

inline std::vector<char> ReadBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), {});
}

inline void WriteBytes(const fs::path& file, const std::vector<char>& bytes) {
  std::ofstream(file, std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// One frame of a constructed TUM sequence: a BGR colour image and 16-bit depth (TUM units,
// 5000 per metre), written as rgb/<t>.png and depth/<t>.png.
struct TumTestFrame {
  double color_time = 0, depth_time = 0;
  cv::Mat bgr;    // CV_8UC3
  cv::Mat depth;  // CV_16UC1
};

// Writes the frames and rgb.txt + depth.txt (no associations.txt) into `dir`.
inline void WriteTumSequence(const fs::path& dir, const std::vector<TumTestFrame>& frames) {
  fs::create_directories(dir / "rgb");
  fs::create_directories(dir / "depth");
  std::ofstream rgb(dir / "rgb.txt"), depth(dir / "depth.txt");
  rgb << "# color images\n# file: 'test'\n# timestamp filename\n";
  depth << "# depth maps\n# file: 'test'\n# timestamp filename\n";
  for (const TumTestFrame& f : frames) {
    char name[64];
    std::snprintf(name, sizeof name, "%.6f.png", f.color_time);
    cv::imwrite((dir / "rgb" / name).string(), f.bgr);
    rgb << std::to_string(f.color_time) << " rgb/" << name << "\n";
    std::snprintf(name, sizeof name, "%.6f.png", f.depth_time);
    cv::imwrite((dir / "depth" / name).string(), f.depth);
    depth << std::to_string(f.depth_time) << " depth/" << name << "\n";
  }
}

// A 640x480 frame pair: mid-grey colour, depth `value` (TUM units) everywhere.
inline TumTestFrame PlainTumFrame(double t, uint16_t value, int depth_width = 640,
                                  int depth_height = 480) {
  return {t, t + 0.005, cv::Mat(480, 640, CV_8UC3, cv::Scalar(90, 120, 150)),
          cv::Mat(depth_height, depth_width, CV_16UC1, cv::Scalar(value))};
}

}  // namespace reenact::capture::testing
