#include "proto/clip/frame_codec.h"

#include <cmath>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/error/check.h"
#include "proto/clip/byte_io.h"
#include "proto/clip/image_probe.h"
#include "proto/clip/json_fields.h"

namespace reenact::proto {
namespace {

using internal::ByteReader;
using internal::ByteWriter;
using internal::JsonField;
using internal::JsonFieldError;
using nlohmann::json;

constexpr char kMagic[4] = {'R', 'F', 'R', 'M'};
constexpr double kRotationTolerance = 1e-6;

// Why a 4x4 matrix is not a rigid transform, or nullopt if it is one.
std::optional<std::string> PoseProblem(const Eigen::Matrix4d& m) {
  if (!m.allFinite()) return "has non-finite entries";
  if (m.row(3) != Eigen::RowVector4d(0, 0, 0, 1)) return "has a last row other than 0 0 0 1";
  const Eigen::Matrix3d r = m.topLeftCorner<3, 3>();
  const double off = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (off > kRotationTolerance) return "has a rotation that is not orthonormal";
  if (r.determinant() < 0) return "has a rotation with determinant -1 (a reflection)";
  return std::nullopt;
}

cv::Mat Wrap(const Image<uint8_t>& image, int type) {
  return cv::Mat(image.height, image.width, type, const_cast<uint8_t*>(image.data.data()));
}

std::vector<uint8_t> Encode(const std::string& ext, const cv::Mat& mat, const std::vector<int>& params) {
  std::vector<uint8_t> out;
  REENACT_CHECK(cv::imencode(ext, mat, out, params), "cv::imencode(" + ext + ") failed");
  return out;
}

json PayloadJson(const char* codec, size_t bytes) { return json{{"codec", codec}, {"bytes", bytes}}; }

Error Corrupt(const std::string& message) { return MakeError("corrupt", "frame: " + message); }

struct Header {
  ClipFrame frame;  // everything but the images
  int width = 0, height = 0;
  uint64_t color_bytes = 0, depth_bytes = 0, mask_bytes = 0;
};

uint64_t PayloadBytes(const JsonField& f, const char* codec) {
  const std::string name = f["codec"].String();
  if (name != codec) f["codec"].Fail("= \"" + name + "\" but must be \"" + codec + "\"");
  return static_cast<uint64_t>(f["bytes"].IntegerIn(1, INT64_MAX));
}

Header HeaderFromJson(const json& document) {
  const JsonField root(document, "frame header");
  root.ExpectObject();
  Header h;
  h.frame.timestamp_s = root["timestamp_s"].Number();

  const JsonField pose = root["world_from_sensor"];
  pose.ExpectArray(16);
  Eigen::Matrix4d m;
  for (int i = 0; i < 16; ++i) m(i / 4, i % 4) = pose[static_cast<size_t>(i)].Number();
  if (const auto problem = PoseProblem(m)) pose.Fail(*problem);
  h.frame.world_from_sensor.matrix() = m;

  const JsonField skeleton = root["skeleton"];
  skeleton.ExpectObject();
  for (const auto& [name, value] : skeleton.json().items())
    if (!JointFromName(name)) skeleton.Fail("names unknown joint \"" + name + "\"");
  for (int i = 0; i < kJointCount; ++i) {
    const JsonField joint = skeleton[JointName(static_cast<Joint>(i))];
    const JsonField position = joint["position"];
    position.ExpectArray(3);
    for (int k = 0; k < 3; ++k)
      h.frame.skeleton_in_world.position[i][k] = position[static_cast<size_t>(k)].Number();
    h.frame.skeleton_in_world.confidence[i] = joint["confidence"].NumberIn({0, 1});
  }

  const JsonField crop = root["crop"];
  h.frame.crop_x = static_cast<int>(crop["x"].IntegerIn(0, INT32_MAX));
  h.frame.crop_y = static_cast<int>(crop["y"].IntegerIn(0, INT32_MAX));
  h.width = static_cast<int>(crop["width"].IntegerIn(1, kMaxFrameSide));
  h.height = static_cast<int>(crop["height"].IntegerIn(1, kMaxFrameSide));

  h.color_bytes = PayloadBytes(root["color"], "jpeg");
  h.depth_bytes = PayloadBytes(root["depth"], "png16");
  h.mask_bytes = PayloadBytes(root["mask"], "png8");
  return h;
}

// Checks an encoded image's own header against the frame header before decoding it.
std::optional<Error> CheckProbe(const std::optional<ImageProbe>& probe, const char* what,
                                const Header& h, int bit_depth, int color_type) {
  if (!probe) return Corrupt(std::string(what) + " payload is not a readable image");
  if (probe->width != h.width || probe->height != h.height)
    return Corrupt(std::string(what) + " image is " + std::to_string(probe->width) + "x" +
                   std::to_string(probe->height) + " but the crop is " + std::to_string(h.width) +
                   "x" + std::to_string(h.height));
  if (probe->bit_depth != bit_depth || probe->color_type != color_type)
    return Corrupt(std::string(what) + " image has the wrong pixel format");
  return std::nullopt;
}

cv::Mat DecodeImage(std::span<const uint8_t> bytes, int flags) {
  const cv::Mat buffer(1, static_cast<int>(bytes.size()), CV_8UC1, const_cast<uint8_t*>(bytes.data()));
  try {
    return cv::imdecode(buffer, flags);
  } catch (const cv::Exception&) {
    return cv::Mat();
  }
}

}  // namespace

void FrameCodecOptions::Check() const {
  REENACT_CHECK(jpeg_quality >= 1 && jpeg_quality <= 100, "jpeg_quality must lie in [1, 100]");
}

std::vector<uint8_t> EncodeFrame(const ClipFrame& f, const FrameCodecOptions& options) {
  options.Check();
  const int w = f.color.width, h = f.color.height;
  REENACT_CHECK(!f.color.empty() && w <= kMaxFrameSide && h <= kMaxFrameSide,
                "frame colour must be non-empty and at most kMaxFrameSide on a side");
  REENACT_CHECK(f.color.channels == 3 && f.depth.channels == 1 && f.mask.channels == 1,
                "frame colour needs 3 channels, depth and mask 1");
  REENACT_CHECK(f.depth.width == w && f.depth.height == h && f.mask.width == w && f.mask.height == h,
                "frame colour, depth and mask must have the same size");
  REENACT_CHECK(f.color.data.size() == static_cast<size_t>(w) * h * 3 &&
                    f.depth.data.size() == static_cast<size_t>(w) * h &&
                    f.mask.data.size() == static_cast<size_t>(w) * h,
                "frame image data size disagrees with width x height x channels");
  REENACT_CHECK(f.crop_x >= 0 && f.crop_y >= 0, "crop origin must be >= 0");
  REENACT_CHECK(std::isfinite(f.timestamp_s), "timestamp must be finite");
  const auto problem = PoseProblem(f.world_from_sensor.matrix());
  REENACT_CHECK(!problem, "world_from_sensor " + problem.value_or(""));

  cv::Mat bgr;
  cv::cvtColor(Wrap(f.color, CV_8UC3), bgr, cv::COLOR_RGB2BGR);
  const std::vector<uint8_t> color =
      Encode(".jpg", bgr, {cv::IMWRITE_JPEG_QUALITY, options.jpeg_quality});
  const cv::Mat depth_mat(h, w, CV_16UC1, const_cast<uint16_t*>(f.depth.data.data()));
  const std::vector<uint8_t> depth = Encode(".png", depth_mat, {});
  const std::vector<uint8_t> mask = Encode(".png", Wrap(f.mask, CV_8UC1), {});

  json pose = json::array();
  for (int i = 0; i < 16; ++i) pose.push_back(f.world_from_sensor.matrix()(i / 4, i % 4));
  json skeleton = json::object();
  for (int i = 0; i < kJointCount; ++i) {
    const Eigen::Vector3d& p = f.skeleton_in_world.position[i];
    const double c = f.skeleton_in_world.confidence[i];
    REENACT_CHECK(p.allFinite() && c >= 0 && c <= 1,
                  "joint positions must be finite and confidences in [0, 1]");
    skeleton[std::string(JointName(static_cast<Joint>(i)))] =
        json{{"position", {p.x(), p.y(), p.z()}}, {"confidence", c}};
  }
  const json header{
      {"timestamp_s", f.timestamp_s},
      {"world_from_sensor", pose},
      {"skeleton", skeleton},
      {"crop", {{"x", f.crop_x}, {"y", f.crop_y}, {"width", w}, {"height", h}}},
      {"color", PayloadJson("jpeg", color.size())},
      {"depth", PayloadJson("png16", depth.size())},
      {"mask", PayloadJson("png8", mask.size())},
  };
  const std::string header_text = header.dump();
  REENACT_CHECK(header_text.size() <= kMaxFrameHeaderBytes, "frame header too large");

  ByteWriter out;
  out.Bytes(std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(kMagic), 4));
  out.U32(kFrameFormatVersion);
  out.U32(static_cast<uint32_t>(header_text.size()));
  out.Text(header_text);
  out.Bytes(color);
  out.Bytes(depth);
  out.Bytes(mask);
  return std::move(out.bytes());
}

Expected<ClipFrame> DecodeFrame(std::span<const uint8_t> bytes) {
  ByteReader in(bytes);
  std::span<const uint8_t> magic;
  if (!in.Take(4, &magic)) return Corrupt("truncated: " + std::to_string(bytes.size()) + " bytes");
  if (!std::equal(magic.begin(), magic.end(), kMagic))
    return Corrupt("bad magic (not an RFRM frame container)");
  uint32_t version = 0, header_length = 0;
  if (!in.U32(&version) || !in.U32(&header_length)) return Corrupt("truncated container header");
  if (version != kFrameFormatVersion)
    return MakeError("unsupported", "frame: container version " + std::to_string(version) +
                                        " is not supported (this build reads " +
                                        std::to_string(kFrameFormatVersion) + ")");
  if (header_length > kMaxFrameHeaderBytes)
    return Corrupt("header length " + std::to_string(header_length) + " exceeds the limit");
  std::span<const uint8_t> header_bytes;
  if (!in.Take(header_length, &header_bytes))
    return Corrupt("truncated: header length " + std::to_string(header_length) + " runs past the end");

  const json document = json::parse(header_bytes.begin(), header_bytes.end(), nullptr, false);
  if (document.is_discarded()) return Corrupt("header is not valid JSON");
  Header h;
  try {
    h = HeaderFromJson(document);
  } catch (const JsonFieldError& e) {
    return Corrupt(std::string(e.what()).substr(std::string("frame ").size()));
  }

  std::span<const uint8_t> color_bytes, depth_bytes, mask_bytes;
  if (!in.Take(h.color_bytes, &color_bytes) || !in.Take(h.depth_bytes, &depth_bytes) ||
      !in.Take(h.mask_bytes, &mask_bytes))
    return Corrupt("truncated: payload lengths run past the end of the container");
  if (in.remaining() != 0)
    return Corrupt(std::to_string(in.remaining()) + " unexpected bytes after the mask payload");

  if (auto e = CheckProbe(ProbeJpeg(color_bytes), "colour", h, 8, 3)) return *e;
  if (auto e = CheckProbe(ProbePng(depth_bytes), "depth", h, 16, 0)) return *e;
  if (auto e = CheckProbe(ProbePng(mask_bytes), "mask", h, 8, 0)) return *e;

  const cv::Mat bgr = DecodeImage(color_bytes, cv::IMREAD_COLOR);
  const cv::Mat depth = DecodeImage(depth_bytes, cv::IMREAD_UNCHANGED);
  const cv::Mat mask = DecodeImage(mask_bytes, cv::IMREAD_UNCHANGED);
  const cv::Size size(h.width, h.height);
  if (bgr.empty() || bgr.type() != CV_8UC3 || bgr.size() != size)
    return Corrupt("colour JPEG does not decode to a " + std::to_string(h.width) + "x" +
                   std::to_string(h.height) + " colour image");
  if (depth.empty() || depth.type() != CV_16UC1 || depth.size() != size)
    return Corrupt("depth PNG does not decode to a 16-bit single-channel image of the crop size");
  if (mask.empty() || mask.type() != CV_8UC1 || mask.size() != size)
    return Corrupt("mask PNG does not decode to an 8-bit single-channel image of the crop size");

  ClipFrame frame = std::move(h.frame);
  frame.color = ImageRgb8(h.width, h.height, 3);
  frame.depth = ImageDepthMm(h.width, h.height, 1);
  frame.mask = ImageGray8(h.width, h.height, 1);
  cv::Mat rgb(h.height, h.width, CV_8UC3, frame.color.data.data());
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  depth.copyTo(cv::Mat(h.height, h.width, CV_16UC1, frame.depth.data.data()));
  mask.copyTo(cv::Mat(h.height, h.width, CV_8UC1, frame.mask.data.data()));
  return frame;
}

}  // namespace reenact::proto
