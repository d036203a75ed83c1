// common/ is Eigen + the standard library only (DESIGN.md): fail if another library leaks in.
// The compiler's own SIMD intrinsics headers (x86 SSE2, Arm NEON) are part of the toolchain,
// not a library, and are allowed.
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include <gtest/gtest.h>

namespace {

TEST(CommonDependencies, IncludesOnlyEigenStdAndCommon) {
  const std::filesystem::path root = std::filesystem::path(REENACT_SOURCE_DIR) / "common";
  const std::regex include_re(R"(^\s*#\s*include\s*([<"])([^>"]+)[>"])");
  int files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    const auto ext = entry.path().extension();
    if (ext != ".h" && ext != ".cc") continue;
    ++files;
    std::ifstream in(entry.path());
    std::string line;
    while (std::getline(in, line)) {
      std::smatch m;
      if (!std::regex_search(line, m, include_re)) continue;
      const std::string header = m[2];
      const bool intrinsics = header == "emmintrin.h" || header == "arm_neon.h";
      const bool ok = header.rfind("common/", 0) == 0 || header.rfind("Eigen/", 0) == 0 ||
                      intrinsics ||
                      (header.find('/') == std::string::npos && header.find('.') == std::string::npos);
      EXPECT_TRUE(ok) << entry.path() << " includes " << header;
    }
  }
  EXPECT_GT(files, 5);
}

}  // namespace
