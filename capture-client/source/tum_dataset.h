#pragma once
// The text files of a TUM RGB-D sequence directory (Sturm et al. 2012), each with '#'
// comment lines and whitespace-separated fields:
//   rgb.txt, depth.txt   "timestamp filename"                (seconds since the Unix epoch,
//                                                              file relative to the folder)
//   associations.txt     "t_rgb rgb_file t_depth depth_file" (made by TUM's associate.py;
//                                                              not part of the download)
//   groundtruth.txt      "timestamp tx ty tz qx qy qz qw"    (world_from_camera of the colour
//                                                              camera's optical centre)
// Without associations.txt, colour and depth images are associated as associate.py does:
// pairs whose timestamps differ by at most max_difference_s (TUM's default 0.02 s: the
// Kinect's streams run at 30 Hz, unsynchronised, so partners are at most ~17 ms apart), each
// image used once, closest pairs first.

#include <filesystem>
#include <string>
#include <vector>

#include "capture-client/source/timed_trajectory.h"
#include "common/error/expected.h"

namespace reenact::capture {

struct TumFramePair {
  double color_time_s = 0;
  std::string color_file;  // relative to the sequence directory, e.g. "rgb/1305031910.765.png"
  double depth_time_s = 0;
  std::string depth_file;
};

struct TumFrameList {
  std::vector<TumFramePair> frames;  // strictly ascending colour time
  std::string listed_in;             // "associations.txt" or "rgb.txt + depth.txt"
};

// The frames of a sequence: associations.txt if present, else rgb.txt and depth.txt
// associated by timestamp. Errors, naming the file and line: "not_found" (neither
// associations.txt nor both of rgb.txt and depth.txt), "corrupt" (a malformed line, a
// non-finite or repeated timestamp), "empty" (no frame, or no pair within the gap).
Expected<TumFrameList> ReadTumFrameList(const std::filesystem::path& dir,
                                        double max_difference_s = 0.02);

// groundtruth.txt as poses in ascending time. Errors: "corrupt" (malformed line, non-finite
// value, a quaternion far from unit length (| |q| - 1 | > 0.01), a repeated or decreasing
// timestamp), naming the line.
Expected<std::vector<TimedPose>> ReadTumTrajectory(const std::filesystem::path& file);

}  // namespace reenact::capture
