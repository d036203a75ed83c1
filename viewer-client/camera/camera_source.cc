#include "viewer-client/camera/camera_source.h"

#include <charconv>

#include "viewer-client/camera/camera_calibration.h"
#include "viewer-client/camera/synthetic_camera_source.h"
#include "viewer-client/camera/tum_directory_source.h"
#include "viewer-client/camera/video_capture_source.h"

namespace reenact::viewer {
namespace {

constexpr const char* kKinds = "tum:DIR, video:FILE, live[:N] or synthetic:SCENARIO";

Expected<PinholeCamera> Calibration(const std::optional<std::filesystem::path>& given,
                                    const std::optional<std::filesystem::path>& fallback,
                                    std::string_view spec) {
  if (given) return LoadCameraCalibration(*given);
  std::error_code ec;
  if (fallback && std::filesystem::exists(*fallback, ec)) return LoadCameraCalibration(*fallback);
  return MakeError("usage", "--camera " + std::string(spec) +
                                " needs the camera's intrinsics: pass --calibration FILE (OpenCV "
                                "YAML/JSON with camera_matrix and distortion_coefficients; "
                                "docs/calibration/ has examples)");
}

}  // namespace

Expected<std::unique_ptr<CameraSource>> OpenCameraSource(
    std::string_view spec, const std::optional<std::filesystem::path>& calibration) {
  const size_t colon = spec.find(':');
  const std::string_view kind = spec.substr(0, colon);
  const std::string_view arg = colon == std::string_view::npos ? "" : spec.substr(colon + 1);
  if (kind == "tum" || kind == "video") {
    if (arg.empty()) {
      return MakeError("usage", "--camera " + std::string(kind) + ": needs a path, e.g. " +
                                    std::string(kind) + (kind == "tum" ? ":DIR" : ":FILE"));
    }
    const std::filesystem::path path(arg);
    std::optional<std::filesystem::path> fallback;
    if (kind == "tum") fallback = path / "calibration.yaml";
    auto camera = Calibration(calibration, fallback, spec);
    if (!camera.ok()) return camera.error();
    return kind == "tum" ? OpenTumDirectorySource(path, *camera)
                         : OpenVideoFileSource(path, *camera);
  }
  if (kind == "live") {
    int index = 0;
    if (colon != std::string_view::npos) {
      const auto [end, ec] = std::from_chars(arg.data(), arg.data() + arg.size(), index);
      if (arg.empty() || ec != std::errc() || end != arg.data() + arg.size() || index < 0) {
        return MakeError("usage", "--camera live:N needs a camera number N >= 0, not '" +
                                      std::string(arg) + "'");
      }
    }
    auto camera = Calibration(calibration, std::nullopt, spec);
    if (!camera.ok()) return camera.error();
    return OpenLiveCameraSource(index, *camera);
  }
  if (kind == "synthetic") {
    if (calibration)
      return MakeError("usage",
                       "--camera synthetic: renders with the scene's own intrinsics: "
                       "drop --calibration");
    if (arg.empty())
      return MakeError("usage",
                       "--camera synthetic: needs a scenario, e.g. synthetic:turn-and-kick");
    return OpenSyntheticCameraSpec(arg);
  }
  return MakeError("usage", "unknown camera '" + std::string(spec) + "': use " + kKinds);
}

}  // namespace reenact::viewer
