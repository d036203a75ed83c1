// Layer rules of DESIGN.md for vision/ and the viewer: vision/ builds on common/, Eigen,
// OpenCV and the standard library only; the viewer never includes capture-client/ (what both
// clients need lives in vision/ or proto/) but for the synthetic scenes (below).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <utility>
#include <vector>

namespace {

// Every quoted or bracketed include of the .h/.cc files below folder, with its file.
std::vector<std::pair<std::string, std::string>> Includes(const std::string& folder) {
  const std::filesystem::path root = std::filesystem::path(REENACT_SOURCE_DIR) / folder;
  const std::regex include_re(R"(^\s*#\s*include\s*[<"]([^>"]+)[>"])");
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    const auto ext = entry.path().extension();
    if (ext != ".h" && ext != ".cc") continue;
    std::ifstream in(entry.path());
    std::string line;
    while (std::getline(in, line)) {
      std::smatch m;
      if (std::regex_search(line, m, include_re)) out.emplace_back(entry.path().string(), m[1]);
    }
  }
  return out;
}

bool StartsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

TEST(VisionDependencies, IncludesOnlyCommonVisionEigenOpenCvAndStd) {
  const auto includes = Includes("vision");
  ASSERT_GT(includes.size(), 10u);
  for (const auto& [file, header] : includes) {
    const bool std_header =
        header.find('/') == std::string::npos && header.find('.') == std::string::npos;
    const bool ok = StartsWith(header, "common/") || StartsWith(header, "vision/") ||
                    StartsWith(header, "Eigen/") || StartsWith(header, "opencv2/") || std_header;
    EXPECT_TRUE(ok) << file << " includes " << header;
  }
}

// The one exception: the synthetic scenes (capture-client/synthetic/, the library
// reenact_synthetic -> common) for the viewer's synthetic camera; they in turn include nothing
// of the capture pipeline.
TEST(VisionDependencies, ViewerNeverIncludesTheCaptureClient) {
  const auto includes = Includes("viewer-client");
  ASSERT_GT(includes.size(), 10u);
  for (const auto& [file, header] : includes) {
    EXPECT_FALSE(StartsWith(header, "capture-client/") &&
                 !StartsWith(header, "capture-client/synthetic/"))
        << file << " includes " << header;
  }
}

TEST(VisionDependencies, SyntheticScenesIncludeNoCapturePipeline) {
  const auto includes = Includes("capture-client/synthetic");
  ASSERT_GT(includes.size(), 10u);
  for (const auto& [file, header] : includes) {
    EXPECT_FALSE(StartsWith(header, "capture-client/") &&
                 !StartsWith(header, "capture-client/synthetic/") &&
                 header != "capture-client/source/text_file.h")
        << file << " includes " << header;
    EXPECT_FALSE(StartsWith(header, "proto/") || StartsWith(header, "vision/") ||
                 StartsWith(header, "viewer-client/"))
        << file << " includes " << header;
  }
}

}  // namespace
