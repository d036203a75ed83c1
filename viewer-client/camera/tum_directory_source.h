#pragma once
// Colour frames of a TUM RGB-D sequence directory (Sturm et al. 2012) in time order, for the
// viewer (the capture client reads the same folders with depth; the viewer needs colour only):
//   rgb.txt            "timestamp filename" per line, '#' comments
//   associations.txt   "t_rgb rgb_file t_depth depth_file", used when rgb.txt is absent
// Filenames are relative to the directory.

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "viewer-client/camera/camera_source.h"

namespace reenact::viewer {

struct TumColorFrame {
  double timestamp_s = 0;
  std::string file;  // relative to the directory
};

// The colour frames listed in dir (rgb.txt, else associations.txt). Errors: "not_found"
// (neither file), "corrupt" naming the file and line (a line with too few fields, a timestamp
// that is not a finite number, timestamps not strictly increasing), "empty" (no frame).
Expected<std::vector<TumColorFrame>> ReadTumColorFrames(const std::filesystem::path& dir);

// A source over those frames with the given intrinsics. Errors: those of
// ReadTumColorFrames. Next() fails naming the image that cannot be decoded or has another
// size than the camera.
Expected<std::unique_ptr<CameraSource>> OpenTumDirectorySource(const std::filesystem::path& dir,
                                                               const PinholeCamera& camera);

}  // namespace reenact::viewer
