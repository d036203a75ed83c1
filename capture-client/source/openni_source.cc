#include "capture-client/source/openni_source.h"

#include <OpenNI.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "capture-client/slam/rolling_shutter.h"
#include "capture-client/source/frame_checks.h"
#include "capture-client/source/oni_file_scan.h"
#include "capture-client/source/openni_runtime.h"
#include "capture-client/source/source_argument.h"

namespace reenact::capture {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr size_t kMaxQueuedFrames = 8;  // per stream, while waiting for a partner

std::string Deg(double rad) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", rad * 180 / kPi);
  return buf;
}

std::string PixelFormatName(openni::PixelFormat f) {
  switch (f) {
    case openni::PIXEL_FORMAT_DEPTH_1_MM:
      return "DEPTH_1_MM";
    case openni::PIXEL_FORMAT_DEPTH_100_UM:
      return "DEPTH_100_UM";
    case openni::PIXEL_FORMAT_SHIFT_9_2:
      return "SHIFT_9_2";
    case openni::PIXEL_FORMAT_SHIFT_9_3:
      return "SHIFT_9_3";
    case openni::PIXEL_FORMAT_RGB888:
      return "RGB888";
    case openni::PIXEL_FORMAT_YUV422:
      return "YUV422";
    case openni::PIXEL_FORMAT_GRAY8:
      return "GRAY8";
    case openni::PIXEL_FORMAT_GRAY16:
      return "GRAY16";
    case openni::PIXEL_FORMAT_JPEG:
      return "JPEG";
    case openni::PIXEL_FORMAT_YUYV:
      return "YUYV";
  }
  return "format " + std::to_string(static_cast<int>(f));
}

bool IsDepthFormat(openni::PixelFormat f) {
  return f == openni::PIXEL_FORMAT_DEPTH_1_MM || f == openni::PIXEL_FORMAT_DEPTH_100_UM;
}
bool IsColorFormat(openni::PixelFormat f) {
  return f == openni::PIXEL_FORMAT_RGB888 || f == openni::PIXEL_FORMAT_YUV422 ||
         f == openni::PIXEL_FORMAT_YUYV || f == openni::PIXEL_FORMAT_GRAY8 ||
         f == openni::PIXEL_FORMAT_JPEG;
}

// One decoded frame of one stream, waiting for its partner.
struct QueuedFrame {
  uint64_t timestamp_us = 0;
  cv::Mat image;  // CV_8UC3 RGB or CV_16UC1 millimetres, full frame, un-mirrored
};

// Places a (possibly cropped) frame into a full frame and undoes mirroring.
cv::Mat FullFrame(const cv::Mat& frame, const openni::VideoFrameRef& ref, int width, int height,
                  bool mirrored) {
  cv::Mat full;
  if (ref.getCroppingEnabled() || frame.cols != width || frame.rows != height) {
    full = cv::Mat::zeros(height, width, frame.type());
    const cv::Rect crop =
        cv::Rect(ref.getCropOriginX(), ref.getCropOriginY(), frame.cols, frame.rows) &
        cv::Rect(0, 0, width, height);
    frame(cv::Rect(0, 0, crop.width, crop.height)).copyTo(full(crop));
  } else {
    full = frame;
  }
  cv::Mat out;
  if (mirrored)
    cv::flip(full, out, 1);
  else
    out = full.data == frame.data ? full.clone() : full;
  return out;
}

}  // namespace

void OpenNiSourceOptions::Check() const {
  REENACT_CHECK(wait_timeout_ms > 0, "wait_timeout_ms must be > 0");
  REENACT_CHECK(std::isfinite(max_pair_gap_s) && max_pair_gap_s >= 0,
                "max_pair_gap_s must be finite and >= 0");
  REENACT_CHECK(max_leading_empty_depth_frames >= 1, "max_leading_empty_depth_frames >= 1");
  if (fov_deg)
    REENACT_CHECK(
        fov_deg->first > 0 && fov_deg->first < 180 && fov_deg->second > 0 && fov_deg->second < 180,
        "fov_deg must be in (0, 180)");
}

PinholeCamera CameraFromFieldOfView(int width, int height, double hfov_rad, double vfov_rad) {
  REENACT_CHECK(width > 0 && height > 0, "camera size must be positive");
  REENACT_CHECK(hfov_rad > 0 && hfov_rad < kPi && vfov_rad > 0 && vfov_rad < kPi,
                "field of view must be in (0, pi)");
  PinholeCamera c;
  c.width = width;
  c.height = height;
  c.fx = width / (2 * std::tan(hfov_rad / 2));
  c.fy = height / (2 * std::tan(vfov_rad / 2));
  c.cx = (width - 1) / 2.0;
  c.cy = (height - 1) / 2.0;
  return c;
}

struct OpenNiSource::Impl {
  openni::Device device;
  openni::VideoStream color, depth;
  bool started = false;
  bool is_file = false;
  bool lacks_cropping = false;  // recording without the cropping property (oni_file_scan.h)
  OpenNiSourceOptions options;
  SensorInfo info;
  std::string where;  // "oni:FILE" / "openni:URI" for messages
  int width = 0, height = 0;
  bool color_mirrored = false, depth_mirrored = false;
  double max_gap_us = 0;
  // Frames of the recording per stream: declared (0 = unknown), found by ScanOniFile, read so
  // far, and the recording's index of the last one read.
  int color_total = 0, depth_total = 0, color_read = 0, depth_read = 0;
  int color_records = 0, depth_records = 0;
  int color_last_index = 0, depth_last_index = 0;
  bool repeating = false;  // the recording is set to repeat (SetUpStreams)
  std::deque<QueuedFrame> color_queue, depth_queue;
  int yielded = 0, dropped = 0;
  DepthPresenceGuard depth_guard{30};

  ~Impl() {
    if (started) {
      color.stop();
      depth.stop();
    }
    color.destroy();
    depth.destroy();
    device.close();
  }

  Status ReadOne(openni::VideoStream& stream, bool is_color);
  Expected<std::optional<SensorFrame>> Next();
  Expected<std::optional<SensorFrame>> PairQueued();
  Expected<std::optional<SensorFrame>> WaitTimedOut() const;
};

Status OpenNiSource::Impl::ReadOne(openni::VideoStream& stream, bool is_color) {
  const std::string kind = is_color ? "colour" : "depth";
  openni::VideoFrameRef ref;
  if (stream.readFrame(&ref) != openni::STATUS_OK || !ref.isValid())
    return MakeError("openni",
                     where + ": reading a " + kind + " frame failed (" + OpenNiLastError() + ")");
  int& last_index = is_color ? color_last_index : depth_last_index;
  const int read = is_color ? color_read : depth_read;
  if (repeating && read > 0 && ref.getFrameIndex() <= last_index)
    return MakeError("corrupt",
                     where + ": the " + kind + " stream's frame " + std::to_string(read + 1) +
                         " (index " + std::to_string(ref.getFrameIndex()) +
                         ") does not follow the one before (index " + std::to_string(last_index) +
                         "): its frames are out of order, or OpenNI2 started the "
                         "recording over; it is damaged, re-record it");
  last_index = ref.getFrameIndex();
  const openni::PixelFormat format = ref.getVideoMode().getPixelFormat();
  const int w = ref.getWidth(), h = ref.getHeight();
  if (w <= 0 || h <= 0 || w > width || h > height)
    return MakeError("corrupt", where + ": a " + kind + " frame of " + std::to_string(w) + "x" +
                                    std::to_string(h) + " does not fit the stream's " +
                                    std::to_string(width) + "x" + std::to_string(height));
  void* data = const_cast<void*>(ref.getData());
  const size_t stride = static_cast<size_t>(ref.getStrideInBytes());
  const size_t bytes = static_cast<size_t>(ref.getDataSize());
  QueuedFrame q;
  q.timestamp_us = ref.getTimestamp();
  cv::Mat decoded;
  const auto short_frame = [&]() {
    return MakeError("corrupt", where + ": a frame holds " + std::to_string(bytes) +
                                    " bytes, too few for " + std::to_string(w) + "x" +
                                    std::to_string(h) + " " + PixelFormatName(format));
  };
  if (is_color) {
    if (format == openni::PIXEL_FORMAT_JPEG) {
      cv::Mat bgr =
          cv::imdecode(cv::Mat(1, static_cast<int>(bytes), CV_8UC1, data), cv::IMREAD_COLOR);
      if (bgr.empty() || bgr.cols != w || bgr.rows != h)
        return MakeError("corrupt", where + ": a JPEG colour frame does not decode");
      cv::cvtColor(bgr, decoded, cv::COLOR_BGR2RGB);
    } else {
      const int type = format == openni::PIXEL_FORMAT_RGB888  ? CV_8UC3
                       : format == openni::PIXEL_FORMAT_GRAY8 ? CV_8UC1
                                                              : CV_8UC2;
      if (stride * (h - 1) + static_cast<size_t>(w) * CV_ELEM_SIZE(type) > bytes)
        return short_frame();
      const cv::Mat raw(h, w, type, data, stride);
      if (format == openni::PIXEL_FORMAT_RGB888)
        decoded = raw;
      else if (format == openni::PIXEL_FORMAT_GRAY8)
        cv::cvtColor(raw, decoded, cv::COLOR_GRAY2RGB);
      else
        cv::cvtColor(raw, decoded,
                     format == openni::PIXEL_FORMAT_YUV422 ? cv::COLOR_YUV2RGB_UYVY
                                                           : cv::COLOR_YUV2RGB_YUYV);
    }
    q.image = FullFrame(decoded, ref, width, height, color_mirrored);
    color_queue.push_back(std::move(q));
    ++color_read;
    if (color_queue.size() > kMaxQueuedFrames) {
      color_queue.pop_front();
      ++dropped;
    }
  } else {
    if (stride * (h - 1) + static_cast<size_t>(w) * 2 > bytes) return short_frame();
    const cv::Mat raw(h, w, CV_16UC1, data, stride);
    if (format == openni::PIXEL_FORMAT_DEPTH_100_UM)
      raw.convertTo(decoded, CV_16UC1, 0.1);  // rounds to the nearest millimetre
    else
      decoded = raw;
    q.image = FullFrame(decoded, ref, width, height, depth_mirrored);
    depth_queue.push_back(std::move(q));
    ++depth_read;
    if (depth_queue.size() > kMaxQueuedFrames) {
      depth_queue.pop_front();
      ++dropped;
    }
  }
  return {};
}

Expected<std::optional<SensorFrame>> OpenNiSource::Impl::Next() {
  while (true) {
    auto paired = PairQueued();
    if (!paired.ok() || paired->has_value()) return paired;

    // A recording whose declared frames are all read has ended.
    const bool color_done = is_file && color_total > 0 && color_read >= color_total;
    const bool depth_done = is_file && depth_total > 0 && depth_read >= depth_total;
    if ((color_done && color_queue.empty()) || (depth_done && depth_queue.empty()) ||
        (color_done && depth_done)) {
      if (Status s = depth_guard.AtEnd(where); !s.ok()) return s.error();
      return std::optional<SensorFrame>();
    }

    openni::VideoStream* streams[2];
    bool is_color[2];
    int n = 0;
    if (!color_done) {
      streams[n] = &color;
      is_color[n++] = true;
    }
    if (!depth_done) {
      streams[n] = &depth;
      is_color[n++] = false;
    }
    int ready = -1;
    const openni::Status waited =
        openni::OpenNI::waitForAnyStream(streams, n, &ready, options.wait_timeout_ms);
    if (waited == openni::STATUS_TIME_OUT || (waited == openni::STATUS_OK && ready < 0))
      return WaitTimedOut();
    if (waited != openni::STATUS_OK)
      return MakeError("openni", where + ": waiting for frames failed (" + OpenNiLastError() + ")");
    if (Status s = ReadOne(*streams[ready], is_color[ready]); !s.ok()) return s.error();
  }
}

// The next pair of queued colour and depth frames close enough in time, dropping the older
// frame of pairs too far apart; nullopt when a queue runs empty first.
Expected<std::optional<SensorFrame>> OpenNiSource::Impl::PairQueued() {
  while (!color_queue.empty() && !depth_queue.empty()) {
    const double dt = static_cast<double>(color_queue.front().timestamp_us) -
                      static_cast<double>(depth_queue.front().timestamp_us);
    if (std::abs(dt) > max_gap_us) {
      (dt < 0 ? color_queue : depth_queue).pop_front();
      ++dropped;
      continue;
    }
    QueuedFrame c = std::move(color_queue.front()), d = std::move(depth_queue.front());
    color_queue.pop_front();
    depth_queue.pop_front();
    SensorFrame frame;
    frame.timestamp_s = static_cast<double>(c.timestamp_us) * 1e-6;
    frame.color = ImageRgb8(width, height, 3);
    frame.depth = ImageDepthMm(width, height, 1);
    c.image.copyTo(cv::Mat(height, width, CV_8UC3, frame.color.data.data()));
    d.image.copyTo(cv::Mat(height, width, CV_16UC1, frame.depth.data.data()));
    const std::string at = where + " frame " + std::to_string(yielded);
    if (Status s = CheckRegisteredPair(frame.color, frame.depth, info.color_camera, at); !s.ok())
      return s.error();
    if (Status s = depth_guard.Observe(frame.depth, where); !s.ok()) return s.error();
    ++yielded;
    return std::optional<SensorFrame>(std::move(frame));
  }
  return std::optional<SensorFrame>();
}

// No frame came within the wait: an error that says why, or the end of a recording that
// declares no length.
Expected<std::optional<SensorFrame>> OpenNiSource::Impl::WaitTimedOut() const {
  const std::string seconds = std::to_string(options.wait_timeout_ms / 1000.0);
  const std::string counts = "after " + std::to_string(color_read) + " colour and " +
                             std::to_string(depth_read) + " depth frames";
  if (!is_file)
    return MakeError("timeout", where + ": no frame within " + seconds + " s " + counts +
                                    ": the device stopped sending (unplugged, or in use by "
                                    "another program?); reconnect it and retry");
  if (color_read == 0 && depth_read == 0)
    return MakeError("timeout",
                     where + ": OpenNI2 yields no frame from this recording (waited " + seconds +
                         " s). " +
                         (lacks_cropping ? "It lacks the cropping property, without which Debian's "
                                           "OpenNI2 2.2 reader yields no frames"
                                         : "Debian's OpenNI2 2.2 reader yields none from some "
                                           "recordings (those without the cropping property)") +
                         "; re-record it, or convert it with another OpenNI build");
  if (color_total <= 0 || depth_total <= 0) {  // no declared length: the end
    if (Status s = depth_guard.AtEnd(where); !s.ok()) return s.error();
    return std::optional<SensorFrame>();
  }
  return MakeError("timeout", where + ": playback stopped " + counts + " of " +
                                  std::to_string(color_total) + " and " +
                                  std::to_string(depth_total) +
                                  " declared; the recording is damaged after that point");
}

OpenNiSource::OpenNiSource(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
OpenNiSource::~OpenNiSource() = default;
const SensorInfo& OpenNiSource::info() const { return impl_->info; }
Expected<std::optional<SensorFrame>> OpenNiSource::Next() { return impl_->Next(); }

namespace {

// Live: asks for 640x480 RGB at 30 Hz and millimetre depth of the same size when offered.
void PickLiveModes(OpenNiSource::Impl& impl) {
  const auto pick = [](openni::VideoStream& s, bool want_color) {
    const auto& modes = s.getSensorInfo().getSupportedVideoModes();
    for (int i = 0; i < modes.getSize(); ++i) {
      const openni::VideoMode& m = modes[i];
      const bool format_ok = want_color ? m.getPixelFormat() == openni::PIXEL_FORMAT_RGB888
                                        : m.getPixelFormat() == openni::PIXEL_FORMAT_DEPTH_1_MM;
      if (format_ok && m.getResolutionX() == 640 && m.getResolutionY() == 480 && m.getFps() == 30) {
        s.setVideoMode(m);
        return;
      }
    }
  };
  pick(impl.color, true);
  pick(impl.depth, false);
  impl.color.setMirroringEnabled(false);
  impl.depth.setMirroringEnabled(false);
}

// Creates both streams, in the live modes for a device.
Status CreateStreams(OpenNiSource::Impl& impl) {
  const std::string& where = impl.where;
  if (!impl.device.hasSensor(openni::SENSOR_COLOR))
    return MakeError("unsupported", where +
                                        " has no colour stream; a colour + depth (RGB-D) "
                                        "recording or device is needed");
  if (!impl.device.hasSensor(openni::SENSOR_DEPTH))
    return MakeError("unsupported", where +
                                        " has no depth stream; a colour + depth (RGB-D) "
                                        "recording or device is needed");
  if (impl.color.create(impl.device, openni::SENSOR_COLOR) != openni::STATUS_OK ||
      impl.depth.create(impl.device, openni::SENSOR_DEPTH) != openni::STATUS_OK)
    return MakeError("openni", where + ": cannot create the colour and depth streams (" +
                                   OpenNiLastError() + ")");
  if (!impl.is_file) PickLiveModes(impl);
  return {};
}

// Checks the streams' pixel formats and that they share one size, which it takes, with their
// mirroring.
Status TakeStreamModes(OpenNiSource::Impl& impl, const openni::VideoMode& cm,
                       const openni::VideoMode& dm) {
  const std::string& where = impl.where;
  if (!IsColorFormat(cm.getPixelFormat()))
    return MakeError("unsupported", where + ": colour pixel format " +
                                        PixelFormatName(cm.getPixelFormat()) +
                                        " is not supported (RGB888, YUV422, YUYV, GRAY8, JPEG)");
  if (!IsDepthFormat(dm.getPixelFormat()))
    return MakeError("unsupported", where + ": depth pixel format " +
                                        PixelFormatName(dm.getPixelFormat()) +
                                        " is not supported (DEPTH_1_MM, DEPTH_100_UM)");
  if (cm.getResolutionX() != dm.getResolutionX() || cm.getResolutionY() != dm.getResolutionY())
    return MakeError("corrupt", where + ": colour is " + std::to_string(cm.getResolutionX()) + "x" +
                                    std::to_string(cm.getResolutionY()) + " but depth is " +
                                    std::to_string(dm.getResolutionX()) + "x" +
                                    std::to_string(dm.getResolutionY()) +
                                    "; registered colour and depth must have one size");
  impl.width = cm.getResolutionX();
  impl.height = cm.getResolutionY();
  if (impl.width <= 0 || impl.height <= 0)
    return MakeError("corrupt", where + ": the streams report no image size");
  impl.color_mirrored = impl.color.getMirroringEnabled();
  impl.depth_mirrored = impl.depth.getMirroringEnabled();
  return {};
}

// The colour camera's field of view (radians) and a note of where it came from: as given,
// else the colour stream's, else the depth stream's.
struct FieldOfView {
  double h = 0, v = 0;
  std::string note;
};

Expected<FieldOfView> StreamFieldOfView(const OpenNiSource::Impl& impl) {
  FieldOfView fov;
  double& hfov = fov.h;
  double& vfov = fov.v;
  if (impl.options.fov_deg) {
    hfov = impl.options.fov_deg->first * kPi / 180;
    vfov = impl.options.fov_deg->second * kPi / 180;
    fov.note = "field of view " + Deg(hfov) + "x" + Deg(vfov) + " deg as given";
    return fov;
  }
  hfov = impl.color.getHorizontalFieldOfView();
  vfov = impl.color.getVerticalFieldOfView();
  fov.note = "colour stream's field of view ";
  if (!(hfov > 0 && hfov < kPi && vfov > 0 && vfov < kPi)) {
    hfov = impl.depth.getHorizontalFieldOfView();
    vfov = impl.depth.getVerticalFieldOfView();
    fov.note = "depth stream's field of view (the colour stream has none) ";
  }
  if (!(hfov > 0 && hfov < kPi && vfov > 0 && vfov < kPi))
    return MakeError("unsupported", impl.where +
                                        " reports no field of view for either stream; "
                                        "give the colour camera's with ?fov=HxV "
                                        "(degrees, e.g. fov=62.7x48.6 for a Kinect v1)");
  fov.note += Deg(hfov) + "x" + Deg(vfov) + " deg";
  return fov;
}

// A recording's declared frame counts, and whether it plays on repeat.
void SetUpPlayback(OpenNiSource::Impl& impl) {
  openni::PlaybackControl* playback = impl.device.getPlaybackControl();
  impl.color_total = playback->getNumberOfFrames(impl.color);
  impl.depth_total = playback->getNumberOfFrames(impl.depth);
  impl.info.frame_count = impl.color_total > 0 && impl.depth_total > 0
                              ? std::min(impl.color_total, impl.depth_total)
                              : -1;
  // Played to its end, OpenNI2's player thread then walks its stream list every 10 ms
  // without a lock, and destroying a stream meanwhile can crash it (docs/decisions.md,
  // Capture). Set to repeat, it instead starts over and waits for the next read, which never
  // comes: Next() ends at the declared counts. Only where the recording holds exactly those
  // counts (ScanOniFile's records; OpenNI2 refused to open the real recording with its
  // counts raised to 13, so this is a second guard), so that no frame is read twice; should
  // the player skip one anyway, ReadOne refuses the frame that starts the recording over.
  impl.repeating = impl.color_total > 0 && impl.color_total == impl.color_records &&
                   impl.depth_total > 0 && impl.depth_total == impl.depth_records;
  if (impl.repeating && playback->setRepeatEnabled(true) != openni::STATUS_OK)
    impl.repeating = false;
}

// Creates both streams, checks their modes, fills the camera and starts them. `impl.where`,
// `options` and `is_file` are set by the caller.
Status SetUpStreams(OpenNiSource::Impl& impl, const std::string& registration_note) {
  const std::string& where = impl.where;
  if (Status created = CreateStreams(impl); !created.ok()) return created.error();
  const openni::VideoMode cm = impl.color.getVideoMode(), dm = impl.depth.getVideoMode();
  if (Status modes = TakeStreamModes(impl, cm, dm); !modes.ok()) return modes.error();
  const Expected<FieldOfView> fov = StreamFieldOfView(impl);
  if (!fov.ok()) return fov.error();
  impl.info.color_camera = CameraFromFieldOfView(impl.width, impl.height, fov->h, fov->v);
  impl.info.depth_camera = impl.info.color_camera;
  impl.info.depth_scale_m = 0.001;
  impl.info.frame_rate_hz = cm.getFps() > 0 ? cm.getFps() : 30;
  impl.max_gap_us = (impl.options.max_pair_gap_s > 0 ? impl.options.max_pair_gap_s
                                                     : 0.5 / impl.info.frame_rate_hz) *
                    1e6;
  if (impl.is_file) SetUpPlayback(impl);
  // Kinect v1 and the Xtion / Carmine class that OpenNI2 drives read colour out alike.
  impl.info.color_readout_ratio = slam::kKinectV1ReadoutRatio;
  char summary[160];
  std::snprintf(summary, sizeof summary, " (%dx%d at %.0f Hz, ", impl.width, impl.height,
                impl.info.frame_rate_hz);
  impl.info.description = where + summary + registration_note + ", " + fov->note +
                          (impl.color_mirrored || impl.depth_mirrored ? ", un-mirrored" : "") + ")";
  impl.depth_guard = DepthPresenceGuard(impl.options.max_leading_empty_depth_frames);

  if (impl.depth.start() != openni::STATUS_OK || impl.color.start() != openni::STATUS_OK)
    return MakeError("openni", where + ": cannot start the streams (" + OpenNiLastError() + ")");
  impl.started = true;
  return {};
}

Expected<std::pair<double, double>> ParseFov(std::string_view kind, const std::string& text) {
  double h = 0, v = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lfx%lf%c", &h, &v, &tail) != 2 || !(h > 0 && h < 180) ||
      !(v > 0 && v < 180))
    return MakeError("usage", std::string(kind) + ": fov=" + text +
                                  " must be HxV in degrees, each in (0, 180), e.g. fov=62.7x48.6");
  return std::make_pair(h, v);
}

Expected<OpenNiSourceOptions> OptionsFrom(std::string_view kind, const SourceArgument& arg) {
  OpenNiSourceOptions options;
  for (const auto& [name, value] : arg.options) {
    if (name == "fov") {
      auto fov = ParseFov(kind, value);
      if (!fov.ok()) return fov.error();
      options.fov_deg = *fov;
    } else if (name == "registered") {
      auto b = ParseBoolOption(kind, name, value);
      if (!b.ok()) return b.error();
      options.assume_registered = *b;
    } else if (name == "timeout_ms") {
      char* end = nullptr;
      const long ms = std::strtol(value.c_str(), &end, 10);
      if (value.empty() || *end != '\0' || ms < 1 || ms > 600000)
        return MakeError("usage", std::string(kind) + ": timeout_ms=" + value +
                                      " must be a whole number of milliseconds in [1, 600000]");
      options.wait_timeout_ms = static_cast<int>(ms);
    }
  }
  return options;
}

}  // namespace

Expected<std::unique_ptr<FrameSource>> OpenNiSource::OpenFile(const std::filesystem::path& file,
                                                              const OpenNiSourceOptions& options) {
  options.Check();
  auto scan = ScanOniFile(file);
  if (!scan.ok()) return scan.error();
  const std::string where = "oni:" + file.string();
  const OniNodeInfo* depth_node = scan->FirstNodeOfType(kOniNodeTypeDepth);
  const OniNodeInfo* image_node = scan->FirstNodeOfType(kOniNodeTypeImage);
  if (depth_node == nullptr || image_node == nullptr)
    return MakeError("unsupported", where + " has no " + (depth_node ? "colour" : "depth") +
                                        " stream; a colour + depth (RGB-D) recording is needed");
  if (depth_node->frame_records == 0 || image_node->frame_records == 0)
    return MakeError("empty", where + ": the " + (depth_node->frame_records ? "colour" : "depth") +
                                  " stream has no frames; record again");

  // Refuse a recording that says its depth is unregistered before OpenNI2 opens it.
  if (depth_node->alternative_view_point && *depth_node->alternative_view_point == 0 &&
      !options.assume_registered)
    return MakeError("unsupported",
                     where +
                         ": depth is not registered to colour in this recording (it was "
                         "recorded with registration off), so colour and depth pixels do "
                         "not correspond; re-record with depth-to-colour registration on");

  if (Status init = InitializeOpenNi(); !init.ok()) return init.error();
  auto impl = std::make_unique<Impl>();
  impl->is_file = true;
  impl->options = options;
  impl->where = where;
  if (impl->device.open(file.c_str()) != openni::STATUS_OK)
    return MakeError("openni", where + ": OpenNI2 cannot open the recording (" + OpenNiLastError() +
                                   "); it is damaged or from an "
                                   "unsupported recorder");
  openni::PlaybackControl* playback = impl->device.getPlaybackControl();
  if (playback == nullptr)
    return MakeError("openni", where + ": OpenNI2 did not open it as a recording");
  // Every frame, in order, once: manual speed and no repeat before the streams start.
  playback->setSpeed(-1);
  playback->setRepeatEnabled(false);

  std::string registration;
  if (depth_node->alternative_view_point)
    registration = *depth_node->alternative_view_point != 0 ? "depth registered to colour" : "";
  else if (impl->device.getImageRegistrationMode() == openni::IMAGE_REGISTRATION_DEPTH_TO_COLOR)
    registration = "depth registered to colour";
  if (registration.empty()) {
    if (!options.assume_registered)
      return MakeError("unsupported",
                       where +
                           ": the recording does not say whether depth is registered to "
                           "colour; if it is, open it as oni:FILE?registered=1");
    registration = "depth registered to colour (as asserted)";
  }
  impl->lacks_cropping = !image_node->has_cropping || !depth_node->has_cropping;
  impl->color_records = static_cast<int>(image_node->frame_records);
  impl->depth_records = static_cast<int>(depth_node->frame_records);
  if (Status s = SetUpStreams(*impl, registration); !s.ok()) return s.error();
  return std::unique_ptr<FrameSource>(new OpenNiSource(std::move(impl)));
}

Expected<std::unique_ptr<FrameSource>> OpenNiSource::OpenDevice(
    const std::string& uri, const OpenNiSourceOptions& options) {
  options.Check();
  if (Status init = InitializeOpenNi(); !init.ok()) return init.error();
  openni::Array<openni::DeviceInfo> all;
  openni::OpenNI::enumerateDevices(&all);
  // OpenNI2 lists every recording this process has opened as a device too: the OniFile
  // driver's "oni File" devices, whose URI is the recording's path.
  std::vector<std::string> uris;
  std::string connected;
  for (int i = 0; i < all.getSize(); ++i) {
    const std::string device_uri = all[i].getUri();
    std::error_code ec;
    if (std::string(all[i].getName()) == "oni File" ||
        (device_uri.size() > 4 && device_uri.compare(device_uri.size() - 4, 4, ".oni") == 0) ||
        std::filesystem::is_regular_file(device_uri, ec))
      continue;
    uris.push_back(all[i].getUri());
    connected += std::string(connected.empty() ? "" : ", ") + all[i].getUri() + " (" +
                 all[i].getVendor() + " " + all[i].getName() + ")";
  }
  if (uris.empty())
    return MakeError("not_found",
                     "no OpenNI2 device found: connect a Kinect, Xtion or Astra (and check that "
                     "this user may access it: Debian's libopenni2-0 installs udev rules, "
                     "replug after installing), or play a recording with --source oni:FILE");
  if (!uri.empty() && std::find(uris.begin(), uris.end(), uri) == uris.end())
    return MakeError("not_found",
                     "no OpenNI2 device with URI '" + uri + "'; connected: " + connected);
  const std::string chosen = uri.empty() ? uris.front() : uri;
  auto impl = std::make_unique<Impl>();
  impl->is_file = false;
  impl->options = options;
  impl->where = "openni:" + chosen;
  if (impl->device.open(chosen.c_str()) != openni::STATUS_OK)
    return MakeError("openni", impl->where + ": cannot open the device (" + OpenNiLastError() +
                                   "); is another program using it?");
  if (!impl->device.isImageRegistrationModeSupported(openni::IMAGE_REGISTRATION_DEPTH_TO_COLOR))
    return MakeError("unsupported", impl->where +
                                        ": the device cannot register depth to "
                                        "colour, which this capture needs");
  if (impl->device.setImageRegistrationMode(openni::IMAGE_REGISTRATION_DEPTH_TO_COLOR) !=
      openni::STATUS_OK)
    return MakeError("openni", impl->where +
                                   ": switching on depth-to-colour registration "
                                   "failed (" +
                                   OpenNiLastError() + ")");
  impl->device.setDepthColorSyncEnabled(true);  // best effort: pairing does not rely on it
  if (Status s = SetUpStreams(*impl, "depth registered to colour"); !s.ok()) return s.error();
  return std::unique_ptr<FrameSource>(new OpenNiSource(std::move(impl)));
}

Expected<std::unique_ptr<FrameSource>> OpenNiSource::OpenFileSpec(const std::string& argument) {
  auto arg = ParseSourceArgument("oni", argument, {"fov", "registered", "timeout_ms"});
  if (!arg.ok()) return arg.error();
  if (arg->path.empty())
    return MakeError("usage", "--source oni:FILE needs a recording, e.g. oni:room.oni");
  auto options = OptionsFrom("oni", *arg);
  if (!options.ok()) return options.error();
  return OpenFile(arg->path, *options);
}

Expected<std::unique_ptr<FrameSource>> OpenNiSource::OpenDeviceSpec(const std::string& argument) {
  auto arg = ParseSourceArgument("openni", argument, {"fov", "timeout_ms"});
  if (!arg.ok()) return arg.error();
  auto options = OptionsFrom("openni", *arg);
  if (!options.ok()) return options.error();
  return OpenDevice(arg->path, *options);
}

}  // namespace reenact::capture
