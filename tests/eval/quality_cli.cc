#include "tests/eval/quality_cli.h"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

namespace reenact::eval {
namespace {

namespace fs = std::filesystem;

Expected<std::vector<std::string>> SplitList(const std::string& flag, const std::string& text) {
  if (text.empty())
    return MakeError("usage", "--" + flag + ": empty list (give a comma-separated list)");
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) out.push_back(item);
  if (text.back() == ',') out.emplace_back();
  for (const std::string& item : out)
    if (item.empty())
      return MakeError("usage", "--" + flag + ": empty item in '" + text +
                                    "' (give a comma-separated list without gaps)");
  return out;
}

Expected<double> ParseFiniteNumber(const std::string& flag, const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(value))
    return MakeError("usage", "--" + flag + ": '" + text + "' is not a finite number");
  return value;
}

Expected<int> ParseFrame(const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || value < 0 ||
      value > 1'000'000)
    return MakeError("usage", "--image-pairs: frame '" + text + "' is not a frame index >= 0");
  return static_cast<int>(value);
}

// The nearest existing ancestor of path (path itself if it exists).
fs::path NearestExisting(const fs::path& path) {
  fs::path p = fs::absolute(path).lexically_normal();
  std::error_code ec;
  while (!fs::exists(p, ec) && p.has_parent_path() && p != p.parent_path()) p = p.parent_path();
  return p;
}

}  // namespace

Expected<std::vector<std::string>> ParseMethodList(const std::string& text) {
  auto list = SplitList("methods", text);
  if (!list.ok()) return list.error();
  if (auto found = FindQualityMethods(*list); !found.ok()) return found.error();
  return list;
}

std::set<std::string> QualityFlags() {
  return {"scenario", "body",   "methods",     "views",          "step",      "json",
          "markdown", "images", "image-pairs", "skeleton-noise", "skeletons", "lighting"};
}

Status CheckWritableFile(const std::string& flag, const std::string& path) {
  const std::string what = "--" + flag + " " + path + ": ";
  if (path.empty()) return MakeError("io", "--" + flag + ": empty path");
  std::error_code ec;
  const fs::path file = fs::absolute(path).lexically_normal();
  if (fs::is_directory(file, ec)) return MakeError("io", what + "is a folder, not a file");
  if (fs::exists(file, ec)) {
    if (::access(file.c_str(), W_OK) != 0)
      return MakeError("io", what + "cannot be written: " + std::strerror(errno));
    return {};
  }
  const fs::path folder = file.parent_path();
  if (!fs::is_directory(folder, ec))
    return MakeError("io",
                     what + "the folder " + folder.string() + " does not exist (create it first)");
  if (::access(folder.c_str(), W_OK | X_OK) != 0)
    return MakeError("io",
                     what + "cannot write into " + folder.string() + ": " + std::strerror(errno));
  return {};
}

Status CheckCreatableFolder(const std::string& flag, const std::string& path) {
  const std::string what = "--" + flag + " " + path + ": ";
  if (path.empty()) return MakeError("io", "--" + flag + ": empty path");
  const fs::path existing = NearestExisting(path);
  std::error_code ec;
  if (!fs::is_directory(existing, ec))
    return MakeError("io", what + existing.string() + " is a file, not a folder");
  if (::access(existing.c_str(), W_OK | X_OK) != 0)
    return MakeError("io",
                     what + "cannot write into " + existing.string() + ": " + std::strerror(errno));
  return {};
}

Expected<QualityCommand> ParseQualityCommand(const CommandLine& cl) {
  QualityCommand command;
  QualityOptions& o = command.options;
  o.scenario = cl.GetOr("scenario", o.scenario);
  if (o.scenario.empty()) return MakeError("usage", "--scenario: empty name");
  o.body = cl.GetOr("body", "");
  if (o.body == "procedural") o.body.clear();
  if (auto text = cl.Get("methods")) {
    auto list = ParseMethodList(*text);
    if (!list.ok()) return list.error();
    o.methods = *list;
  }
  if (auto text = cl.Get("views")) {
    auto list = SplitList("views", *text);
    if (!list.ok()) return list.error();
    o.views_deg.clear();
    for (const std::string& item : *list) {
      auto v = ParseFiniteNumber("views", item);
      if (!v.ok()) return v.error();
      o.views_deg.push_back(*v);
    }
  }
  const auto step = cl.GetInt("step", o.frame_step);
  if (!step.ok()) return step.error();
  if (*step < 1 || *step > 1'000'000)
    return MakeError("usage", "--step must be a whole number >= 1 (every K-th frame), got " +
                                  std::to_string(*step));
  o.frame_step = static_cast<int>(*step);
  const auto noise = cl.GetDouble("skeleton-noise", o.skeleton_noise_m);
  if (!noise.ok()) return noise.error();
  if (!std::isfinite(*noise) || *noise < 0 || *noise > 1)
    return MakeError("usage", "--skeleton-noise must be metres in [0, 1] (e.g. 0.02), got " +
                                  std::to_string(*noise));
  o.skeleton_noise_m = *noise;
  const std::string skeletons = cl.GetOr("skeletons", "truth");
  if (skeletons != "truth" && skeletons != "track")
    return MakeError("usage", "--skeletons must be truth or track, got '" + skeletons + "'");
  o.tracked_skeletons = skeletons == "track";
  if (o.tracked_skeletons && o.skeleton_noise_m > 0)
    return MakeError("usage",
                     "--skeletons track and --skeleton-noise exclude each other (the tracker's "
                     "skeletons carry their own error)");
  const std::string lighting = cl.GetOr("lighting", "scene");
  if (lighting != "scene" && lighting != "flat")
    return MakeError("usage", "--lighting must be scene or flat, got '" + lighting + "'");
  o.flat_lighting = lighting == "flat";

  if (auto text = cl.Get("image-pairs")) {
    if (!cl.Has("images"))
      return MakeError("usage", "--image-pairs needs --images DIR to write the pictures into");
    auto list = SplitList("image-pairs", *text);
    if (!list.ok()) return list.error();
    for (const std::string& item : *list) {
      const size_t at = item.find('@');
      if (at == std::string::npos)
        return MakeError("usage", "--image-pairs: '" + item + "' is not FRAME@DEG (e.g. 90@60)");
      auto frame = ParseFrame(item.substr(0, at));
      if (!frame.ok()) return frame.error();
      auto view = ParseFiniteNumber("image-pairs", item.substr(at + 1));
      if (!view.ok()) return view.error();
      o.image_pairs.push_back({*frame, *view});
    }
  }
  if (auto dir = cl.Get("images")) {
    if (Status s = CheckCreatableFolder("images", *dir); !s.ok()) return s.error();
    o.image_dir = *dir;
  }
  for (const char* flag : {"json", "markdown"})
    if (auto path = cl.Get(flag)) {
      if (Status s = CheckWritableFile(flag, *path); !s.ok()) return s.error();
      (flag == std::string("json") ? command.json_path : command.markdown_path) = *path;
    }
  return command;
}

}  // namespace reenact::eval
