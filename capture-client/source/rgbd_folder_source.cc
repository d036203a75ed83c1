#include "capture-client/source/rgbd_folder_source.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <future>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "capture-client/source/camera_calibration_file.h"
#include "capture-client/source/source_argument.h"
#include "proto/clip/image_probe.h"

namespace reenact::capture {
namespace {

namespace fs = std::filesystem;

constexpr const char* kLayout =
    "rgbd:DIR needs DIR/depth/ of 16-bit PNGs, optionally DIR/rgb/ or DIR/color/, and "
    "DIR/camera.json or DIR/calibration.yml (or ?calibration=FILE)";

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string Size(int width, int height) {
  std::string s = std::to_string(width);
  s += 'x';
  s += std::to_string(height);
  return s;
}

std::string Number(double v) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), v);
  return std::string(buffer, result.ptr);
}

// The first `limit` bytes of a file (fewer if it is shorter); nullopt if it cannot be read.
std::optional<std::vector<uint8_t>> ReadHead(const fs::path& path, size_t limit) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::vector<uint8_t> bytes(limit);
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(limit));
  bytes.resize(static_cast<size_t>(in.gcount()));
  return bytes;
}

// A stem of digits only, as a number (at most 18 digits).
std::optional<uint64_t> FrameNumber(const std::string& stem) {
  if (stem.empty() || stem.size() > 18) return std::nullopt;
  uint64_t n = 0;
  for (char c : stem) {
    if (c < '0' || c > '9') return std::nullopt;
    n = n * 10 + static_cast<uint64_t>(c - '0');
  }
  return n;
}

// `number` written as wide as `like` (zero-padded when `like` is).
std::string NumberedLike(uint64_t number, const std::string& like) {
  std::string s = std::to_string(number);
  if (s.size() < like.size()) s.insert(0, like.size() - s.size(), '0');
  return s;
}

struct DepthListing {
  std::vector<fs::path> files;
  Status status;
};

// The .png files of `depth_dir` in frame order (see the header).
DepthListing ListDepthFiles(const fs::path& depth_dir, const std::string& where) {
  DepthListing out;
  std::vector<fs::path> files;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(depth_dir, ec)) {
    std::error_code type_ec;
    if (e.is_regular_file(type_ec) && Lower(e.path().extension().string()) == ".png")
      files.push_back(e.path());
  }
  if (ec) {
    out.status = MakeError("io", where + ": cannot list depth/: " + ec.message());
    return out;
  }
  if (files.empty()) {
    out.status = MakeError("not_found", where + ": depth/ holds no .png depth images; " + kLayout);
    return out;
  }
  std::vector<std::pair<uint64_t, fs::path>> numbered;
  for (const fs::path& f : files) {
    const std::optional<uint64_t> n = FrameNumber(f.stem().string());
    if (!n) break;
    numbered.emplace_back(*n, f);
  }
  if (numbered.size() != files.size()) {  // names, not numbers: in name order
    std::sort(files.begin(), files.end());
    out.files = std::move(files);
    return out;
  }
  std::sort(numbered.begin(), numbered.end());
  for (size_t i = 1; i < numbered.size(); ++i) {
    const auto& [before, before_file] = numbered[i - 1];
    const auto& [n, file] = numbered[i];
    if (n == before) {
      out.status = MakeError("corrupt", where + ": depth/" + before_file.filename().string() +
                                            " and depth/" + file.filename().string() +
                                            " are both frame " + std::to_string(n) + "; keep one");
      return out;
    }
    if (n != before + 1) {
      const std::string missing = NumberedLike(before + 1, before_file.stem().string()) + ".png";
      out.status = MakeError(
          "corrupt", where + ": depth/" + missing + " is missing (the numbered frames go from " +
                         before_file.filename().string() + " to " + file.filename().string() +
                         "); a frame was lost in the export: restore it or renumber the files");
      return out;
    }
  }
  for (auto& [n, f] : numbered) out.files.push_back(std::move(f));
  return out;
}

// PNG depth header checks: 16-bit greyscale, every image of the first one's size.
Expected<std::pair<int, int>> ProbeDepthFiles(const std::vector<fs::path>& files,
                                              const std::string& where) {
  std::optional<std::pair<int, int>> size;
  for (const fs::path& f : files) {
    const std::string name = "depth/" + f.filename().string();
    const auto head = ReadHead(f, 33);
    if (!head) return MakeError("io", where + ": cannot read " + name);
    const std::optional<proto::ImageProbe> probe = proto::ProbePng(*head);
    if (!probe)
      return MakeError("corrupt", where + ": " + name +
                                      " is not a PNG image; depth must be 16-bit single-channel "
                                      "PNGs");
    if (probe->bit_depth != 16 || probe->color_type != 0)
      return MakeError("corrupt",
                       where + ": " + name + " is a " + std::to_string(probe->bit_depth) +
                           "-bit PNG of colour type " + std::to_string(probe->color_type) +
                           ", not 16-bit single-channel (greyscale); depth images "
                           "hold one 16-bit depth value per pixel");
    if (!size) {
      size.emplace(probe->width, probe->height);
    } else if (probe->width != size->first || probe->height != size->second) {
      return MakeError("corrupt", where + ": " + name + " is " + Size(probe->width, probe->height) +
                                      " but depth/" + files.front().filename().string() + " is " +
                                      Size(size->first, size->second) +
                                      "; all depth images must have one size");
    }
  }
  return *size;
}

// The size of a PNG or JPEG colour image from its header.
Expected<std::pair<int, int>> ProbeColorFile(const fs::path& file, const std::string& name,
                                             const std::string& where) {
  std::error_code ec;
  const auto bytes = ReadHead(file, static_cast<size_t>(fs::file_size(file, ec)));
  if (!bytes || ec) return MakeError("io", where + ": cannot read " + name);
  std::optional<proto::ImageProbe> probe = proto::ProbePng(*bytes);
  if (!probe) probe = proto::ProbeJpeg(*bytes);
  if (!probe) return MakeError("corrupt", where + ": " + name + " is not a PNG or JPEG image");
  return std::make_pair(probe->width, probe->height);
}

// The colour image beside each depth image (see the header); empty without a colour folder.
Expected<std::vector<fs::path>> FindColorFiles(const fs::path& dir,
                                               const std::vector<fs::path>& depth_files,
                                               const std::string& where) {
  std::error_code ec;
  const bool rgb = fs::is_directory(dir / "rgb", ec), color = fs::is_directory(dir / "color", ec);
  if (rgb && color)
    return MakeError("usage", where +
                                  ": has both rgb/ and color/; keep the one folder of colour "
                                  "images registered to depth/");
  if (!rgb && !color) return std::vector<fs::path>();
  const std::string folder = rgb ? "rgb" : "color";
  std::vector<fs::path> files;
  size_t missing = 0;
  std::string first_missing;
  for (const fs::path& depth : depth_files) {
    const std::string stem = depth.stem().string();
    std::optional<fs::path> found;
    for (const char* ext : {".png", ".jpg", ".jpeg"}) {
      const fs::path candidate = dir / folder / (stem + ext);
      if (fs::is_regular_file(candidate, ec)) {
        found = candidate;
        break;
      }
    }
    if (!found && missing++ == 0) first_missing = folder + "/" + stem + ".png";
    files.push_back(found.value_or(fs::path()));
  }
  if (missing > 0)
    return MakeError("not_found",
                     where + ": " + first_missing + " (or .jpg) is missing: " +
                         std::to_string(missing) + " of " + std::to_string(depth_files.size()) +
                         " depth images have no colour image of the same name in " + folder + "/");
  return files;
}

// ?calibration=FILE, else the one calibration file in DIR.
Expected<fs::path> FindCalibration(const fs::path& dir, const RgbdFolderOptions& options,
                                   const std::string& where) {
  if (options.calibration) return *options.calibration;
  std::vector<fs::path> present;
  std::error_code ec;
  for (const char* name :
       {"camera.json", "calibration.yml", "calibration.yaml", "calibration.json"})
    if (fs::is_regular_file(dir / name, ec)) present.push_back(dir / name);
  if (present.empty())
    return MakeError("not_found",
                     where +
                         ": no camera.json or calibration.yml/.yaml/.json; give the camera's "
                         "intrinsics in one of them (capture-client/source/"
                         "camera_calibration_file.h) or pass ?calibration=FILE");
  if (present.size() > 1)
    return MakeError("usage", where + ": both " + present[0].filename().string() + " and " +
                                  present[1].filename().string() +
                                  " give the camera; keep one or choose with ?calibration=FILE");
  return present.front();
}

// The camera of the images flipped left-right (u' = W-1-u): the same lens seen in a mirror.
PinholeCamera Flipped(const PinholeCamera& c) {
  PinholeCamera f = c;
  f.cx = (c.width - 1) - c.cx;
  f.distortion.p2 = -c.distortion.p2;
  return f;
}

Expected<double> PositiveOption(const std::string& name, const std::string& value,
                                double max = HUGE_VAL) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || end != value.c_str() + value.size() || errno != 0 || !std::isfinite(v) ||
      !(v > 0) || v > max)
    return MakeError("usage", "rgbd: " + name + "=" + value + " must be a number > 0" +
                                  (max < HUGE_VAL ? " and <= " + Number(max) : std::string()));
  return v;
}

}  // namespace

void RgbdFolderOptions::Check() const {
  REENACT_CHECK(
      !depth_unit_m || (std::isfinite(*depth_unit_m) && *depth_unit_m > 0 && *depth_unit_m <= 1),
      "depth_unit_m must be in (0, 1]");
  REENACT_CHECK(!fps || (std::isfinite(*fps) && *fps > 0), "fps must be finite and > 0");
  REENACT_CHECK(max_leading_empty_depth_frames >= 1, "max_leading_empty_depth_frames >= 1");
}

Expected<std::unique_ptr<RgbdFolderSource>> RgbdFolderSource::Open(
    const fs::path& dir, const RgbdFolderOptions& options) {
  options.Check();
  const std::string where = "rgbd:" + dir.string();
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    return MakeError("not_found", where + ": no such directory; " + kLayout);
  if (!fs::is_directory(dir / "depth", ec))
    return MakeError("not_found", where + ": no depth/ folder; " + kLayout);
  std::unique_ptr<RgbdFolderSource> source(new RgbdFolderSource());
  source->dir_ = dir;
  source->options_ = options;

  DepthListing listing = ListDepthFiles(dir / "depth", where);
  if (!listing.status.ok()) return listing.status.error();
  source->depth_files_ = std::move(listing.files);
  auto color = FindColorFiles(dir, source->depth_files_, where);
  if (!color.ok()) return color.error();
  source->color_files_ = std::move(color).value();

  auto calibration_path = FindCalibration(dir, options, where);
  if (!calibration_path.ok()) return calibration_path.error();
  source->calibration_file_ = *calibration_path;
  auto calibration = ReadCameraCalibrationFile(*calibration_path);
  if (!calibration.ok())
    return MakeError(calibration.error().code, where + ": " + calibration.error().message);

  const auto depth_size = ProbeDepthFiles(source->depth_files_, where);
  if (!depth_size.ok()) return depth_size.error();
  const auto [width, height] = *depth_size;
  const std::string calibration_name = calibration_path->filename().string();
  PinholeCamera camera = calibration->camera;
  if (camera.width > 0 && (camera.width != width || camera.height != height))
    return MakeError("corrupt", where + ": the depth images are " + Size(width, height) + " but " +
                                    calibration_name + " is for " +
                                    Size(camera.width, camera.height) +
                                    " images; use the calibration of this resolution");
  const size_t count = source->depth_files_.size();
  if (calibration->frames && static_cast<size_t>(*calibration->frames) != count)
    return MakeError("corrupt", where + ": " + calibration_name + " says " +
                                    std::to_string(*calibration->frames) +
                                    " frames but depth/ holds " + std::to_string(count) +
                                    " images; the folder is incomplete or the file belongs to "
                                    "another sequence");
  if (!source->color_files_.empty()) {
    const fs::path& first = source->color_files_.front();
    const std::string name =
        first.parent_path().filename().string() + "/" + first.filename().string();
    const auto color_size = ProbeColorFile(first, name, where);
    if (!color_size.ok()) return color_size.error();
    if (*color_size != *depth_size)
      return MakeError("corrupt", where + ": " + name + " is " +
                                      Size(color_size->first, color_size->second) +
                                      " but the depth images are " + Size(width, height) +
                                      "; colour must be registered to depth (same pixel grid)");
  }
  camera.width = width;
  camera.height = height;
  source->file_camera_ = camera;
  source->mirrored_ = options.mirrored.value_or(calibration->mirrored.value_or(false));
  source->depth_unit_m_ = options.depth_unit_m.value_or(calibration->depth_unit_m.value_or(0.001));
  const double fps = options.fps.value_or(calibration->fps.value_or(30.0));

  const bool has_color = !source->color_files_.empty();
  PinholeCamera frame_camera = source->mirrored_ ? Flipped(camera) : camera;
  RgbdFolderOptions::Undistort undistort = options.undistort;
  if (!has_color && undistort == RgbdFolderOptions::Undistort::kColor)
    undistort = RgbdFolderOptions::Undistort::kNone;
  source->options_.undistort = undistort;
  std::string camera_note = "no distortion";
  if (!frame_camera.distortion.IsZero()) {
    if (undistort == RgbdFolderOptions::Undistort::kNone) {
      camera_note = "images not undistorted (camera with distortion)";
    } else {
      source->undistorter_.emplace(frame_camera);
      frame_camera = source->undistorter_->undistorted_camera();
      camera_note = undistort == RgbdFolderOptions::Undistort::kBoth
                        ? "images undistorted"
                        : "colour undistorted, depth as recorded";
    }
  }

  SensorInfo& info = source->info_;
  info.color_camera = frame_camera;
  info.depth_camera = frame_camera;
  info.depth_scale_m = 0.001;
  info.frame_rate_hz = fps;
  info.frame_count = static_cast<int>(count);
  info.has_color = has_color;
  std::string description = where;
  description += " (" + std::to_string(count) + " frames, " + Size(width, height) + ", ";
  if (has_color) {
    description += "colour from ";
    description += source->color_files_.front().parent_path().filename().string();
    description += '/';
  } else {
    description += "depth only";
  }
  description += ", camera from " + calibration_name + ", " + camera_note;
  description += ", depth unit " + Number(source->depth_unit_m_) + " m, " + Number(fps) + " fps";
  if (source->mirrored_) description += ", mirrored images flipped";
  description += ')';
  info.description = std::move(description);
  source->depth_guard_ = DepthPresenceGuard(options.max_leading_empty_depth_frames);
  return source;
}

Expected<std::unique_ptr<RgbdFolderSource>> RgbdFolderSource::OpenSpec(
    const std::string& argument) {
  auto arg = ParseSourceArgument("rgbd", argument,
                                 {"calibration", "depth_unit", "fps", "mirrored", "undistort"});
  if (!arg.ok()) return arg.error();
  if (arg->path.empty())
    return MakeError("usage", std::string("--source rgbd:DIR needs a folder; ") + kLayout);
  RgbdFolderOptions options;
  const auto& o = arg->options;
  if (auto it = o.find("calibration"); it != o.end()) {
    if (it->second.empty()) return MakeError("usage", "rgbd: calibration= needs a file");
    options.calibration = it->second;
  }
  if (auto it = o.find("depth_unit"); it != o.end()) {
    auto v = PositiveOption("depth_unit", it->second, 1.0);
    if (!v.ok()) return v.error();
    options.depth_unit_m = *v;
  }
  if (auto it = o.find("fps"); it != o.end()) {
    auto v = PositiveOption("fps", it->second);
    if (!v.ok()) return v.error();
    options.fps = *v;
  }
  if (auto it = o.find("mirrored"); it != o.end()) {
    auto v = ParseBoolOption("rgbd", "mirrored", it->second);
    if (!v.ok()) return v.error();
    options.mirrored = *v;
  }
  if (auto it = o.find("undistort"); it != o.end()) {
    const std::string& v = it->second;
    if (v == "both" || v == "1")
      options.undistort = RgbdFolderOptions::Undistort::kBoth;
    else if (v == "color" || v == "colour")
      options.undistort = RgbdFolderOptions::Undistort::kColor;
    else if (v == "none" || v == "0")
      options.undistort = RgbdFolderOptions::Undistort::kNone;
    else
      return MakeError("usage", "rgbd: undistort=" + v + " must be both, color or none");
  }
  return Open(arg->path, options);
}

Expected<std::optional<SensorFrame>> RgbdFolderSource::Next() {
  if (next_ >= depth_files_.size()) {
    if (Status s = depth_guard_.AtEnd(info_.description); !s.ok()) return s.error();
    return std::optional<SensorFrame>();
  }
  const size_t index = next_;
  const std::string where = "rgbd:" + dir_.string() + " frame " + std::to_string(index);
  const fs::path& depth_path = depth_files_[index];
  const bool has_color = info_.has_color;
  const fs::path* color_path = has_color ? &color_files_[index] : nullptr;
  for (const fs::path* p : {&depth_path, color_path}) {
    std::error_code ec;
    if (p && !fs::is_regular_file(*p, ec))
      return MakeError("not_found", where + ": " + p->string() + " no longer exists");
  }
  // PNG decoding is nearly all of a frame's time: colour and depth decode concurrently.
  auto depth_read = std::async(std::launch::async, [&depth_path] {
    return cv::imread(depth_path.string(), cv::IMREAD_UNCHANGED);
  });
  cv::Mat bgr;
  if (has_color) bgr = cv::imread(color_files_[index].string(), cv::IMREAD_COLOR);
  const cv::Mat raw = depth_read.get();
  const int w = file_camera_.width, h = file_camera_.height;
  if (raw.empty())
    return MakeError("corrupt", where + ": " + depth_path.string() + " is not a readable image");
  if (raw.type() != CV_16UC1 || raw.cols != w || raw.rows != h)
    return MakeError("corrupt", where + ": " + depth_path.string() + " is no longer a " +
                                    Size(w, h) + " 16-bit single-channel PNG");
  if (has_color && bgr.empty())
    return MakeError("corrupt",
                     where + ": " + color_files_[index].string() + " is not a readable image");
  if (has_color && (bgr.cols != w || bgr.rows != h))
    return MakeError("corrupt", where + ": " + color_files_[index].string() + " is " +
                                    Size(bgr.cols, bgr.rows) + " but the depth is " + Size(w, h) +
                                    "; colour must be registered to depth (same pixel grid)");

  SensorFrame frame;
  frame.timestamp_s = static_cast<double>(index) / info_.frame_rate_hz;
  frame.depth = ImageDepthMm(w, h, 1);
  const double to_mm = depth_unit_m_ / 0.001;
  const bool convert = depth_unit_m_ != 0.001;
  for (int y = 0; y < h; ++y) {
    const uint16_t* in = raw.ptr<uint16_t>(y);
    uint16_t* out = &frame.depth.at(0, y);
    for (int x = 0; x < w; ++x) {
      const uint16_t d = in[mirrored_ ? w - 1 - x : x];
      out[x] = convert ? static_cast<uint16_t>(std::min(65535.0, std::round(d * to_mm))) : d;
    }
  }
  if (has_color) {
    if (mirrored_) cv::flip(bgr, bgr, 1);
    frame.color = ImageRgb8(w, h, 3);
    cv::cvtColor(bgr, cv::Mat(h, w, CV_8UC3, frame.color.data.data()), cv::COLOR_BGR2RGB);
  }
  if (undistorter_) {
    if (has_color) frame.color = undistorter_->Undistort(frame.color);
    if (options_.undistort == RgbdFolderOptions::Undistort::kBoth)
      frame.depth = undistorter_->UndistortDepth(frame.depth);
  }
  if (Status s = depth_guard_.Observe(frame.depth, info_.description); !s.ok()) return s.error();
  ++next_;
  return std::optional<SensorFrame>(std::move(frame));
}

}  // namespace reenact::capture
