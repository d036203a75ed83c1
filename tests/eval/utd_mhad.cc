#include "tests/eval/utd_mhad.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <tuple>

namespace reenact::eval {
namespace {

namespace fs = std::filesystem;

// ../shared/data/README.md's names of the actions 1-27.
constexpr std::array<std::string_view, 27> kActionNames = {
    "right arm swipe to the left",
    "right arm swipe to the right",
    "right hand wave",
    "two-hand front clap",
    "right arm throw",
    "cross arms in the chest",
    "basketball shoot",
    "draw x",
    "draw circle clockwise",
    "draw circle counter-clockwise",
    "draw triangle",
    "bowling",
    "front boxing",
    "baseball swing",
    "tennis forehand",
    "arm curl",
    "tennis serve",
    "two-hand push",
    "knock on door",
    "catch an object",
    "pick up and throw",
    "jogging in place",
    "walking in place",
    "sit to stand",
    "stand to sit",
    "forward lunge",
    "squat"};

// A whole number >= 1 without sign or leading zero, the whole of text.
std::optional<int> PositiveNumber(std::string_view text) {
  if (text.empty() || text.size() > 6 || text[0] < '1' || text[0] > '9') return std::nullopt;
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

}  // namespace

std::optional<UtdMhadSequence> ParseUtdMhadName(std::string_view name) {
  const size_t s = name.find("_s"), t = name.find("_t");
  if (name.size() < 8 || name[0] != 'a' || s == std::string_view::npos ||
      t == std::string_view::npos || t < s)
    return std::nullopt;
  const auto action = PositiveNumber(name.substr(1, s - 1));
  const auto subject = PositiveNumber(name.substr(s + 2, t - s - 2));
  const auto trial = PositiveNumber(name.substr(t + 2));
  if (!action || !subject || !trial || *action > 27) return std::nullopt;
  UtdMhadSequence out;
  out.name = std::string(name);
  out.action = *action;
  out.subject = *subject;
  out.trial = *trial;
  return out;
}

std::string_view UtdMhadActionName(int action) {
  return action >= 1 && action <= 27 ? kActionNames[action - 1] : std::string_view();
}

Expected<std::vector<UtdMhadSequence>> ListUtdMhad(const std::string& root) {
  std::error_code ec;
  if (!fs::is_directory(root, ec))
    return MakeError("not_found", "utd-mhad: " + root +
                                      " is not a folder (give the folder that holds the "
                                      "aA_sS_tT sequence folders, e.g. ../shared/data/utd-mhad)");
  std::vector<UtdMhadSequence> out;
  for (const fs::directory_entry& e : fs::directory_iterator(root, ec)) {
    if (!e.is_directory()) continue;
    auto sequence = ParseUtdMhadName(e.path().filename().string());
    if (!sequence) continue;
    sequence->dir = e.path().string();
    out.push_back(std::move(*sequence));
  }
  if (ec) return MakeError("io", "utd-mhad: cannot list " + root + ": " + ec.message());
  if (out.empty())
    return MakeError("usage", "utd-mhad: " + root +
                                  " holds no sequence folder named aA_sS_tT (e.g. a1_s1_t1); "
                                  "give the data set's root folder");
  std::sort(out.begin(), out.end(), [](const UtdMhadSequence& a, const UtdMhadSequence& b) {
    return std::tie(a.action, a.subject, a.trial) < std::tie(b.action, b.subject, b.trial);
  });
  return out;
}

std::string UtdMhadDepthSpec(const UtdMhadSequence& sequence) {
  return "rgbd:" + sequence.dir + "?mirrored=1";
}

std::string UtdMhadSkeletonPath(const UtdMhadSequence& sequence) {
  return (fs::path(sequence.dir) / "skeleton.txt").string();
}

std::string UtdMhadSkeletonSpec(const UtdMhadSequence& sequence) {
  return "kinect:" + UtdMhadSkeletonPath(sequence) + "?variant=utd-mhad";
}

Expected<std::vector<std::optional<JointPoints>>> ReadUtdMhadJoints20(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return MakeError("not_found", "utd-mhad: no file " + path);
  std::ifstream in(path);
  if (!in) return MakeError("io", "utd-mhad: cannot read " + path);
  std::vector<double> values;
  std::string token;
  while (in >> token) {
    double v = 0;
    const auto [end, err] = std::from_chars(token.data(), token.data() + token.size(), v);
    if (err != std::errc() || end != token.data() + token.size() || !std::isfinite(v))
      return MakeError("corrupt", "utd-mhad: " + path + ": '" + token +
                                      "' is not a finite number (number " +
                                      std::to_string(values.size() + 1) + ")");
    values.push_back(v);
  }
  if (values.empty() || values.size() % 60 != 0)
    return MakeError("corrupt", "utd-mhad: " + path + " holds " + std::to_string(values.size()) +
                                    " numbers, not a whole number of frames of 20 joints x 3");
  std::vector<std::optional<JointPoints>> frames;
  for (size_t f = 0; f < values.size() / 60; ++f) {
    JointPoints& pose = frames.emplace_back().emplace(20);
    for (int j = 0; j < 20; ++j) {
      const Eigen::Vector3d p(values[f * 60 + j * 3], values[f * 60 + j * 3 + 1],
                              values[f * 60 + j * 3 + 2]);
      if (!p.isZero(0)) pose[j] = p;
    }
  }
  return frames;
}

}  // namespace reenact::eval
