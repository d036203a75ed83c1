#include "capture-client/source/tum_dataset.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "common/align/trajectory_error.h"

namespace reenact::capture {
namespace {

namespace fs = std::filesystem;

// Non-comment, non-blank lines of a text file with their 1-based numbers.
Expected<std::vector<std::pair<int, std::string>>> ReadLines(const fs::path& file) {
  std::ifstream in(file);
  if (!in) return MakeError("io", file.string() + ": cannot read the file");
  std::vector<std::pair<int, std::string>> lines;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    lines.emplace_back(number, line);
  }
  return lines;
}

Error Malformed(const fs::path& file, int line, const std::string& expected) {
  return MakeError("corrupt", file.string() + " line " + std::to_string(line) + ": expected \"" +
                                  expected +
                                  "\"; the file is damaged or not "
                                  "a TUM RGB-D list");
}

struct TimedFile {
  double time = 0;
  std::string file;
  int line = 0;
};

Expected<std::vector<TimedFile>> ReadTimedFiles(const fs::path& file) {
  auto lines = ReadLines(file);
  if (!lines.ok()) return lines.error();
  std::vector<TimedFile> out;
  for (const auto& [number, text] : *lines) {
    std::istringstream fields(text);
    TimedFile f;
    f.line = number;
    if (!(fields >> f.time >> f.file) || !std::isfinite(f.time))
      return Malformed(file, number, "timestamp filename");
    out.push_back(f);
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const TimedFile& a, const TimedFile& b) { return a.time < b.time; });
  for (size_t i = 1; i < out.size(); ++i)
    if (out[i].time == out[i - 1].time)
      return MakeError("corrupt", file.string() + " lines " + std::to_string(out[i - 1].line) +
                                      " and " + std::to_string(out[i].line) +
                                      " have the same timestamp; each image needs its own");
  return out;
}

}  // namespace

Expected<TumFrameList> ReadTumFrameList(const fs::path& dir, double max_difference_s) {
  TumFrameList list;
  std::error_code ec;
  const fs::path associations = dir / "associations.txt";
  if (fs::is_regular_file(associations, ec)) {
    list.listed_in = "associations.txt";
    auto lines = ReadLines(associations);
    if (!lines.ok()) return lines.error();
    std::vector<int> line_of;
    for (const auto& [number, text] : *lines) {
      std::istringstream fields(text);
      TumFramePair p;
      if (!(fields >> p.color_time_s >> p.color_file >> p.depth_time_s >> p.depth_file) ||
          !std::isfinite(p.color_time_s) || !std::isfinite(p.depth_time_s))
        return Malformed(associations, number, "t_rgb rgb_file t_depth depth_file");
      list.frames.push_back(p);
      line_of.push_back(number);
    }
    std::vector<size_t> order(list.frames.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
      return list.frames[a].color_time_s < list.frames[b].color_time_s;
    });
    std::vector<TumFramePair> sorted;
    for (size_t k = 0; k < order.size(); ++k) {
      if (k > 0 && list.frames[order[k]].color_time_s == list.frames[order[k - 1]].color_time_s)
        return MakeError("corrupt", associations.string() + " lines " +
                                        std::to_string(line_of[order[k - 1]]) + " and " +
                                        std::to_string(line_of[order[k]]) +
                                        " list the same colour timestamp");
      sorted.push_back(list.frames[order[k]]);
    }
    list.frames = std::move(sorted);
  } else {
    const fs::path rgb = dir / "rgb.txt", depth = dir / "depth.txt";
    const bool has_rgb = fs::is_regular_file(rgb, ec), has_depth = fs::is_regular_file(depth, ec);
    if (!has_rgb || !has_depth)
      return MakeError(
          "not_found",
          dir.string() + " is not a TUM RGB-D sequence: it has no associations.txt" +
              (has_rgb || has_depth ? std::string(" and no ") + (has_rgb ? "depth.txt" : "rgb.txt")
                                    : std::string(" and neither rgb.txt nor depth.txt")) +
              "; point tum: at an unpacked rgbd_dataset_* folder");
    list.listed_in = "rgb.txt + depth.txt";
    auto colors = ReadTimedFiles(rgb);
    if (!colors.ok()) return colors.error();
    auto depths = ReadTimedFiles(depth);
    if (!depths.ok()) return depths.error();
    std::vector<double> color_times, depth_times;
    for (const TimedFile& f : *colors) color_times.push_back(f.time);
    for (const TimedFile& f : *depths) depth_times.push_back(f.time);
    for (const auto& [d, c] : AssociateByTimestamp(depth_times, color_times, max_difference_s))
      list.frames.push_back(
          {(*colors)[c].time, (*colors)[c].file, (*depths)[d].time, (*depths)[d].file});
  }
  if (list.frames.empty())
    return MakeError(
        "empty", dir.string() + ": " + list.listed_in + " yields no colour + depth pair" +
                     (list.listed_in == "associations.txt"
                          ? std::string()
                          : " within " + std::to_string(max_difference_s) + " s of each other") +
                     "; the sequence is empty or its lists do not match");
  return list;
}

Expected<std::vector<TimedPose>> ReadTumTrajectory(const fs::path& file) {
  auto lines = ReadLines(file);
  if (!lines.ok()) return lines.error();
  std::vector<TimedPose> poses;
  for (const auto& [number, text] : *lines) {
    std::istringstream fields(text);
    double t, x, y, z, qx, qy, qz, qw;
    if (!(fields >> t >> x >> y >> z >> qx >> qy >> qz >> qw))
      return Malformed(file, number, "timestamp tx ty tz qx qy qz qw");
    for (double v : {t, x, y, z, qx, qy, qz, qw})
      if (!std::isfinite(v)) return Malformed(file, number, "timestamp tx ty tz qx qy qz qw");
    const Eigen::Quaterniond q(qw, qx, qy, qz);
    if (std::abs(q.norm() - 1) > 0.01)
      return MakeError("corrupt", file.string() + " line " + std::to_string(number) +
                                      ": the orientation is not a unit quaternion (|q| = " +
                                      std::to_string(q.norm()) + ")");
    if (!poses.empty() && t <= poses.back().timestamp_s)
      return MakeError("corrupt", file.string() + " line " + std::to_string(number) +
                                      ": timestamps must increase from line to line");
    poses.push_back({t, Eigen::Vector3d(x, y, z), q.normalized()});
  }
  return poses;
}

}  // namespace reenact::capture
