#include "capture-client/source/tum_camera.h"

#include <algorithm>
#include <cctype>

namespace reenact::capture {
namespace {

std::string Lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

constexpr TumCamera kAll[] = {TumCamera::kFreiburg1, TumCamera::kFreiburg2, TumCamera::kFreiburg3};

}  // namespace

std::string_view TumCameraName(TumCamera camera) {
  switch (camera) {
    case TumCamera::kFreiburg1:
      return "fr1";
    case TumCamera::kFreiburg2:
      return "fr2";
    case TumCamera::kFreiburg3:
      return "fr3";
  }
  return "fr?";
}

PinholeCamera TumColorCamera(TumCamera camera) {
  switch (camera) {
    case TumCamera::kFreiburg1:
      return {640, 480, 517.3, 516.5, 318.6, 255.3, {0.2624, -0.9531, -0.0054, 0.0026, 1.1633}};
    case TumCamera::kFreiburg2:
      return {640, 480, 520.9, 521.0, 325.1, 249.7, {0.2312, -0.7849, -0.0033, -0.0001, 0.9172}};
    case TumCamera::kFreiburg3:
      return {640, 480, 535.4, 539.2, 320.1, 247.6, {}};
  }
  return {};
}

Expected<TumCamera> ParseTumCamera(std::string_view name) {
  const std::string lower = Lower(name);
  for (TumCamera c : kAll) {
    const std::string fr(TumCameraName(c));
    if (lower == fr || lower == "freiburg" + fr.substr(2)) return c;
  }
  return MakeError("usage", "tum: camera=" + std::string(name) +
                                " is not a TUM RGB-D sensor; use camera=fr1, fr2 or fr3");
}

std::optional<TumCamera> DetectTumCamera(std::string_view directory_name) {
  const std::string lower = Lower(directory_name);
  std::optional<TumCamera> found;
  for (TumCamera c : kAll) {
    const std::string fr(TumCameraName(c));
    if (lower.find(fr) == std::string::npos &&
        lower.find("freiburg" + fr.substr(2)) == std::string::npos)
      continue;
    if (found) return std::nullopt;  // names two sensors
    found = c;
  }
  return found;
}

}  // namespace reenact::capture
