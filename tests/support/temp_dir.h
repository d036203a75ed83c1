#pragma once
// A fresh directory under the system's temporary directory, removed with everything in it
// when the object goes.

#include <stdlib.h>

#include <filesystem>
#include <string>
#include <system_error>

#include "common/error/check.h"

namespace reenact::test_support {

class TempDir {
 public:
  explicit TempDir(const std::string& prefix = "reenact-test") {
    std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
    REENACT_CHECK(mkdtemp(pattern.data()) != nullptr, "mkdtemp failed for " + pattern);
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace reenact::test_support
