#include "viewer-client/camera/synthetic_camera_source.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "common/error/check.h"

namespace reenact::viewer {
namespace {

class SyntheticCameraSource : public CameraSource {
 public:
  SyntheticCameraSource(capture::SyntheticScene scene, const SyntheticCameraOptions& options)
      : scene_(std::move(scene)), options_(options) {
    const int n = options.frames > 0 ? options.frames : scene_.frame_count();
    capture::HandheldOptions hand;
    hand.seed = options.seed;
    path_ = MakeSyntheticViewerPath(scene_, n, options.max_deg, hand);
    char text[160];
    std::snprintf(text, sizeof text, "synthetic:%s (%d frames, +-%g degrees%s)",
                  scene_.scenario().c_str(), n, options.max_deg,
                  options.draw_subject ? ", with the subject" : "");
    description_ = text;
  }

  std::string description() const override { return description_; }
  const PinholeCamera& camera() const override { return scene_.sensor_camera(); }

  Expected<std::optional<CameraFrame>> Next() override {
    if (next_ >= path_.world_from_viewer.size()) return std::optional<CameraFrame>();
    const int k = static_cast<int>(next_++);
    capture::SyntheticRenderOptions render;
    render.draw_subject = options_.draw_subject;
    CameraFrame frame;
    frame.timestamp_s = k / scene_.frame_rate_hz();
    frame.true_world_from_viewer = path_.world_from_viewer[k];
    frame.color =
        scene_.Render(k % scene_.frame_count(), camera(), path_.world_from_viewer[k], render).color;
    return std::optional<CameraFrame>(std::move(frame));
  }

 private:
  capture::SyntheticScene scene_;
  SyntheticCameraOptions options_;
  SyntheticViewerPath path_;
  std::string description_;
  size_t next_ = 0;
};

struct SpecArgument {
  std::string scenario;
  std::vector<std::pair<std::string, std::string>> options;  // in the spec's order
};

// "SCENARIO?name=value&name=value": the scenario ends at the last '?' (a scenario such as
// bvh:FILE may hold one itself when followed by an empty query).
Expected<SpecArgument> SplitSpec(std::string_view argument) {
  static const std::set<std::string> kKnown = {"frames", "max_deg", "subject",
                                               "seed",   "body",    "body_height"};
  SpecArgument out;
  const size_t q = argument.rfind('?');
  out.scenario = std::string(argument.substr(0, q));
  if (q == std::string_view::npos) return out;
  std::string_view rest = argument.substr(q + 1);
  while (!rest.empty()) {
    const size_t amp = rest.find('&');
    const std::string_view item = rest.substr(0, amp);
    rest = amp == std::string_view::npos ? std::string_view() : rest.substr(amp + 1);
    const size_t eq = item.find('=');
    const std::string name(item.substr(0, eq));
    if (eq == std::string_view::npos || name.empty())
      return MakeError("usage", "--camera synthetic: option '" + std::string(item) +
                                    "' must be NAME=VALUE (frames, max_deg, subject, seed, body, "
                                    "body_height)");
    if (!kKnown.count(name))
      return MakeError("usage", "--camera synthetic: unknown option '" + name +
                                    "'; options: frames, max_deg, subject, seed, body, "
                                    "body_height");
    for (const auto& [seen, value] : out.options)
      if (seen == name)
        return MakeError("usage", "--camera synthetic: option '" + name + "' given twice");
    out.options.emplace_back(name, std::string(item.substr(eq + 1)));
  }
  return out;
}

Error OptionError(const std::string& name, const std::string& value, const std::string& must) {
  return MakeError("usage", "--camera synthetic: " + name + "=" + value + " " + must);
}

Expected<long long> WholeNumber(const std::string& name, const std::string& value, long long lo,
                                long long hi) {
  long long n = 0;
  const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), n);
  if (value.empty() || ec != std::errc() || end != value.data() + value.size() || n < lo || n > hi)
    return OptionError(
        name, value,
        "must be a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return n;
}

}  // namespace

SyntheticViewerPath MakeSyntheticViewerPath(const capture::SyntheticScene& scene, int n,
                                            double max_deg, const capture::HandheldOptions& hand) {
  REENACT_CHECK(n >= 2, "a viewer path needs at least 2 frames");
  REENACT_CHECK(std::isfinite(max_deg) && max_deg > 0 && max_deg <= 90, "max_deg in (0, 90]");
  const Eigen::Vector3d centre = scene.skeleton_in_world(0)[Joint::kWaist];
  const Eigen::Vector3d up = scene.world_up();
  const Eigen::Vector3d eye0 = scene.world_from_sensor(0).translation();
  SyntheticViewerPath out;
  std::vector<Eigen::Vector3d> path, target;
  for (int k = 0; k < n; ++k) {
    const double a = max_deg * std::sin(2 * std::numbers::pi * k / (n - 1));
    const Eigen::AngleAxisd turn(a * std::numbers::pi / 180, up);
    path.push_back(centre + turn * (eye0 - centre));
    target.push_back(centre);
    out.angle_deg.push_back(a);
  }
  out.world_from_viewer = capture::HandheldSensorPoses(path, target, scene.frame_rate_hz(), hand);
  return out;
}

void SyntheticCameraOptions::Check() const {
  REENACT_CHECK(frames == 0 || frames >= 2, "frames must be 0 or >= 2");
  REENACT_CHECK(std::isfinite(max_deg) && max_deg > 0 && max_deg <= 90, "max_deg in (0, 90]");
}

std::unique_ptr<CameraSource> OpenSyntheticCameraSource(capture::SyntheticScene scene,
                                                        const SyntheticCameraOptions& options) {
  options.Check();
  return std::make_unique<SyntheticCameraSource>(std::move(scene), options);
}

Expected<std::unique_ptr<CameraSource>> OpenSyntheticCameraSpec(std::string_view argument) {
  auto arg = SplitSpec(argument);
  if (!arg.ok()) return arg.error();
  if (arg->scenario.empty())
    return MakeError("usage", "--camera synthetic: needs a scenario, e.g. synthetic:turn-and-kick");
  SyntheticCameraOptions options;
  capture::SyntheticBodySpec body;
  for (const auto& [name, value] : arg->options) {
    if (name == "frames") {
      auto n = WholeNumber(name, value, 2, 1'000'000);
      if (!n.ok()) return n.error();
      options.frames = static_cast<int>(*n);
    } else if (name == "seed") {
      auto n = WholeNumber(name, value, 0, 1LL << 62);
      if (!n.ok()) return n.error();
      options.seed = static_cast<uint64_t>(*n);
    } else if (name == "subject") {
      if (value != "0" && value != "1")
        return OptionError(name, value, "must be 0 (the room alone) or 1 (with the subject)");
      options.draw_subject = value == "1";
    } else if (name == "body") {
      if (value != "procedural") body.gltf_path = value;
    } else {  // max_deg, body_height: numbers
      char* end = nullptr;
      const double x = std::strtod(value.c_str(), &end);
      const bool number = !value.empty() && *end == '\0' && std::isfinite(x);
      if (name == "max_deg") {
        if (!number || x <= 0 || x > 90)
          return OptionError(name, value, "must be a number of degrees in (0, 90]");
        options.max_deg = x;
      } else {
        if (!number || x <= 0 || x >= 10)
          return OptionError(name, value, "must be a height in metres in (0, 10)");
        body.height_m = x;
      }
    }
  }
  if (body.height_m > 0 && !body.skinned())
    return MakeError("usage",
                     "--camera synthetic: body_height needs body=FILE.glb (the procedural body "
                     "has a fixed size)");
  auto scene = capture::SyntheticScene::Create(arg->scenario, 1, body);
  if (!scene.ok()) return scene.error();
  return OpenSyntheticCameraSource(std::move(scene).value(), options);
}

}  // namespace reenact::viewer
