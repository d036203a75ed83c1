#include "capture-client/skeleton/kinect_v1_skeleton.h"

#include <charconv>
#include <cmath>
#include <system_error>
#include <vector>

#include "common/io/text_file.h"
#include "common/skeleton/joint_maps.h"

namespace reenact::capture {
namespace {

constexpr int kKinectJoints = 20;
constexpr size_t kUtKinectNumbers = 1 + 3 * kKinectJoints;  // frame number + 20 x (x, y, z)
constexpr size_t kRowNumbers = 4;                           // x y z c (or u v d c)
constexpr size_t kXyzNumbers = 3;                           // x y z (UTD-MHAD)

struct Line {
  int number = 0;  // 1-based line in the file
  std::vector<double> values;
};

std::string Number(double v) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), v);
  return std::string(buffer, result.ptr);
}

Error Corrupt(const std::string& name, int line, const std::string& what) {
  return MakeError("corrupt", name + " line " + std::to_string(line) + ": " + what);
}

std::string Quoted(const std::string& token, std::string_view what) {
  std::string out = "\"";
  out += token;
  out += "\" ";
  out += what;
  return out;
}

// The non-blank lines of `text` as numbers.
Expected<std::vector<Line>> Tokenize(std::string_view text, const std::string& name) {
  std::vector<Line> lines;
  int number = 0;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view raw = text.substr(start, end - start);
    start = end + 1;
    ++number;
    Line line{number, {}};
    size_t at = 0;
    while (true) {
      at = raw.find_first_not_of(" \t\r\f\v,", at);
      if (at == std::string_view::npos) break;
      size_t stop = raw.find_first_of(" \t\r\f\v,", at);
      if (stop == std::string_view::npos) stop = raw.size();
      std::string_view token = raw.substr(at, stop - at);
      at = stop;
      const std::string shown(token);
      if (token.size() > 1 && token.front() == '+') token.remove_prefix(1);
      double v = 0;
      const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
      const bool parsed = ec == std::errc() && ptr == token.data() + token.size();
      if (ec == std::errc::result_out_of_range || (parsed && !std::isfinite(v)))
        return Corrupt(name, number, Quoted(shown, "is not a finite number"));
      if (!parsed)
        return Corrupt(name, number,
                       Quoted(shown,
                              "is not a number; the file is damaged or not a Kinect "
                              "skeleton text file"));
      line.values.push_back(v);
    }
    if (!line.values.empty()) lines.push_back(std::move(line));
  }
  return lines;
}

bool AllZero(const Eigen::Vector3d& p) { return p.x() == 0 && p.y() == 0 && p.z() == 0; }

// Checks that the present joints of one frame can be metres in skeleton space.
Status CheckMetres(const std::array<Eigen::Vector3d, kKinectJoints>& joints, double max_m,
                   const std::string& name, int line, std::string_view screen_hint) {
  for (const Eigen::Vector3d& p : joints) {
    if (AllZero(p)) continue;
    if (std::abs(p.x()) <= max_m && std::abs(p.y()) <= max_m && p.z() > 0 && p.z() <= max_m)
      continue;
    return MakeError(
        "unsupported",
        name + " line " + std::to_string(line) + ": joint (" + Number(p.x()) + ", " +
            Number(p.y()) + ", " + Number(p.z()) +
            ") is not a position in metres in front of the sensor (|x|, |y| <= " + Number(max_m) +
            ", 0 < z <= " + Number(max_m) +
            "); screen coordinates or millimetres are not supported" + std::string(screen_hint));
  }
  return {};
}

bool IsCount(double v) { return v >= 0 && v <= 9.0e15 && v == std::floor(v); }

struct Parsed {
  std::vector<SkeletonTrackFrame> frames;
  std::string format;
  std::string notes;
};

void AddFrame(const std::array<Eigen::Vector3d, kKinectJoints>& joints, int64_t index,
              Parsed* out) {
  bool any = false;
  for (const Eigen::Vector3d& p : joints) any = any || !AllZero(p);
  if (!any) return;  // untracked frame: no skeleton
  SkeletonTrackFrame frame;
  frame.frame_index = index;
  frame.skeleton_in_sensor = KinectSdkJointsToSkeleton(joints);
  out->frames.push_back(std::move(frame));
}

Expected<Parsed> ParseUtKinect(const std::vector<Line>& lines, const std::string& name,
                               const KinectV1ReadOptions& options) {
  Parsed out;
  out.format = "UTKinect-Action3D";
  std::optional<int64_t> last;
  int repeated = 0;
  for (const Line& line : lines) {
    if (line.values.size() != kUtKinectNumbers)
      return Corrupt(name, line.number,
                     "has " + std::to_string(line.values.size()) + " numbers, expected " +
                         std::to_string(kUtKinectNumbers) +
                         " (a frame number and x y z of 20 joints); a truncated line?");
    if (!IsCount(line.values[0]))
      return Corrupt(name, line.number,
                     "frame number " + Number(line.values[0]) + " is not an integer >= 0");
    const auto n = static_cast<int64_t>(line.values[0]);
    if (last && n < *last)
      return Corrupt(name, line.number,
                     "frame number " + std::to_string(n) + " comes after frame " +
                         std::to_string(*last) + "; frame numbers must not go backwards");
    if (last && n == *last) {
      ++repeated;
      continue;
    }
    last = n;
    std::array<Eigen::Vector3d, kKinectJoints> joints;
    for (int j = 0; j < kKinectJoints; ++j)
      joints[j] =
          Eigen::Vector3d(line.values[1 + 3 * j], line.values[2 + 3 * j], line.values[3 + 3 * j]);
    if (Status s = CheckMetres(joints, options.max_metres, name, line.number, ""); !s.ok())
      return s.error();
    AddFrame(joints, n, &out);
  }
  if (repeated > 0)
    out.notes = "; " + std::to_string(repeated) + " repeated frame number" +
                (repeated == 1 ? "" : "s") + " skipped";
  return out;
}

Expected<Parsed> ParseMsrAction3d(const std::vector<Line>& lines, const std::string& name,
                                  const KinectV1ReadOptions& options) {
  Parsed out;
  out.format = "MSR Action3D real-world";
  for (const Line& line : lines)
    if (line.values.size() != kRowNumbers)
      return Corrupt(name, line.number,
                     "has " + std::to_string(line.values.size()) +
                         " numbers, expected 4 (x y z c of one joint); a truncated line?");
  if (lines.size() % kKinectJoints != 0)
    return Corrupt(name, lines.back().number,
                   "the file ends inside a frame: " + std::to_string(lines.size()) +
                       " joint lines is not a multiple of 20 (20 joints per frame); a "
                       "truncated file?");
  const std::array<int, 20>& to_sdk = MsrAction3dToKinectSdk();
  for (size_t f = 0; f < lines.size() / kKinectJoints; ++f) {
    std::array<Eigen::Vector3d, kKinectJoints> joints;
    for (int k = 0; k < kKinectJoints; ++k) {
      const std::vector<double>& v = lines[f * kKinectJoints + k].values;
      joints[to_sdk[k]] = Eigen::Vector3d(v[0], v[1], v[2]);
    }
    if (Status s = CheckMetres(joints, options.max_metres, name, lines[f * kKinectJoints].number,
                               " (MSR Action3D: read aXX_sYY_eZZ_skeleton3D.txt, the real-world "
                               "coordinates, not aXX_sYY_eZZ_skeleton.txt)");
        !s.ok())
      return s.error();
    AddFrame(joints, static_cast<int64_t>(f), &out);
  }
  return out;
}

Expected<Parsed> ParseUtdMhad(const std::vector<Line>& lines, const std::string& name,
                              const KinectV1ReadOptions& options) {
  Parsed out;
  out.format = "UTD-MHAD";
  for (const Line& line : lines)
    if (line.values.size() != kXyzNumbers)
      return Corrupt(name, line.number,
                     "has " + std::to_string(line.values.size()) +
                         " numbers, expected 3 (x y z of one joint); a truncated line?");
  if (lines.size() % kKinectJoints != 0)
    return Corrupt(name, lines.back().number,
                   "the file ends inside a frame: " + std::to_string(lines.size()) +
                       " joint lines is not a multiple of 20 (20 joints per frame); a "
                       "truncated file?");
  const std::array<int, 20>& to_sdk = UtdMhadToKinectSdk();
  for (size_t f = 0; f < lines.size() / kKinectJoints; ++f) {
    std::array<Eigen::Vector3d, kKinectJoints> joints;
    for (int k = 0; k < kKinectJoints; ++k) {
      const std::vector<double>& v = lines[f * kKinectJoints + k].values;
      joints[to_sdk[k]] = Eigen::Vector3d(v[0], v[1], v[2]);
    }
    if (Status s =
            CheckMetres(joints, options.max_metres, name, lines[f * kKinectJoints].number, "");
        !s.ok())
      return s.error();
    AddFrame(joints, static_cast<int64_t>(f), &out);
  }
  return out;
}

Expected<Parsed> ParseMsrDaily(const std::vector<Line>& lines, const std::string& name,
                               const KinectV1ReadOptions& options) {
  Parsed out;
  out.format = "MSR DailyActivity3D real-world";
  const Line& header = lines.front();
  if (header.values.size() != 2 || !IsCount(header.values[0]) || !IsCount(header.values[1]))
    return Corrupt(name, header.number,
                   "expected the header \"frames joints\" (two integers >= 0)");
  if (header.values[1] != kKinectJoints)
    return Corrupt(name, header.number,
                   "the header announces " + Number(header.values[1]) +
                       " joints per skeleton; Kinect v1 files have 20");
  const auto frame_count = static_cast<int64_t>(header.values[0]);
  size_t at = 1;
  for (int64_t f = 0; f < frame_count; ++f) {
    if (at >= lines.size())
      return Corrupt(name, lines.back().number,
                     "the file ends after " + std::to_string(f) + " of the " +
                         std::to_string(frame_count) +
                         " frames its header announces; a "
                         "truncated file?");
    const Line& count = lines[at++];
    if (count.values.size() != 1 || !IsCount(count.values[0]) ||
        std::fmod(count.values[0], 2 * kKinectJoints) != 0)
      return Corrupt(name, count.number,
                     "expected the row count of frame " + std::to_string(f) +
                         " (0, 40 or 80: two rows per joint per skeleton)");
    const auto rows = static_cast<size_t>(count.values[0]);
    if (lines.size() - at < rows)
      return Corrupt(name, lines.back().number,
                     "the file ends inside frame " + std::to_string(f) + "; a truncated file?");
    for (size_t r = 0; r < rows; ++r)
      if (lines[at + r].values.size() != kRowNumbers)
        return Corrupt(name, lines[at + r].number,
                       "has " + std::to_string(lines[at + r].values.size()) +
                           " numbers, expected 4 (x y z c or u v depth c of one joint); a "
                           "truncated line?");
    if (rows > 0) {
      std::array<Eigen::Vector3d, kKinectJoints> joints;
      for (int j = 0; j < kKinectJoints; ++j) {
        const std::vector<double>& v = lines[at + 2 * j].values;  // the real-world row
        joints[j] = Eigen::Vector3d(v[0], v[1], v[2]);
      }
      if (Status s = CheckMetres(joints, options.max_metres, name, lines[at].number, ""); !s.ok())
        return s.error();
      AddFrame(joints, f, &out);
    }
    at += rows;
  }
  if (at != lines.size())
    return Corrupt(name, lines[at].number,
                   "data after the " + std::to_string(frame_count) +
                       " frames the header announces; the header or the file is damaged");
  return out;
}

}  // namespace

std::string_view KinectTextVariantName(KinectTextVariant variant) {
  switch (variant) {
    case KinectTextVariant::kDetect:
      return "detect";
    case KinectTextVariant::kUtKinect:
      return "utkinect";
    case KinectTextVariant::kMsrAction3d:
      return "msr-action3d";
    case KinectTextVariant::kMsrDailyActivity3d:
      return "msr-daily";
    case KinectTextVariant::kUtdMhad:
      return "utd-mhad";
  }
  return "detect";
}

std::optional<KinectTextVariant> KinectTextVariantFromName(std::string_view name) {
  for (KinectTextVariant v :
       {KinectTextVariant::kDetect, KinectTextVariant::kUtKinect, KinectTextVariant::kMsrAction3d,
        KinectTextVariant::kMsrDailyActivity3d, KinectTextVariant::kUtdMhad})
    if (KinectTextVariantName(v) == name) return v;
  return std::nullopt;
}

void KinectV1ReadOptions::Check() const {
  REENACT_CHECK(std::isfinite(max_metres) && max_metres > 0, "max_metres must be finite and > 0");
  lookup.Check();
}

Eigen::Vector3d SensorFromKinectSkeletonSpace(const Eigen::Vector3d& p_kinect) {
  return Eigen::Vector3d(-p_kinect.x(), -p_kinect.y(), p_kinect.z());
}

const std::array<int, 20>& MsrAction3dToKinectSdk() {
  // Kinect SDK indices: 0 HipCenter, 1 Spine, 2 ShoulderCenter, 3 Head, 4 ShoulderLeft,
  // 5 ElbowLeft, 6 WristLeft, 7 HandLeft, 8 ShoulderRight, 9 ElbowRight, 10 WristRight,
  // 11 HandRight, 12 HipLeft, 13 KneeLeft, 14 AnkleLeft, 15 FootLeft, 16 HipRight,
  // 17 KneeRight, 18 AnkleRight, 19 FootRight.
  static const std::array<int, 20> order = {8, 4,  2, 1,  16, 12, 0,  9,  5,  10,
                                            6, 11, 7, 17, 13, 18, 14, 19, 15, 3};
  return order;
}

const std::array<int, 20>& UtdMhadToKinectSdk() {
  // head, shoulder_center, spine, hip_center, then the limbs in the SDK's own order.
  static const std::array<int, 20> order = {3,  2,  1,  0,  4,  5,  6,  7,  8,  9,
                                            10, 11, 12, 13, 14, 15, 16, 17, 18, 19};
  return order;
}

Skeleton KinectSdkJointsToSkeleton(const std::array<Eigen::Vector3d, 20>& joints_in_kinect) {
  std::array<Eigen::Vector3d, kKinectJoints> positions;
  std::array<double, kKinectJoints> confidences;
  for (int j = 0; j < kKinectJoints; ++j) {
    positions[j] = SensorFromKinectSkeletonSpace(joints_in_kinect[j]);
    confidences[j] = AllZero(joints_in_kinect[j]) ? 0.0 : 1.0;
  }
  return MapSkeleton(KinectV1Joints(), positions, confidences).value();
}

Expected<SkeletonTrack> ParseKinectV1SkeletonText(std::string_view text, const std::string& name,
                                                  const KinectV1ReadOptions& options) {
  options.Check();
  Expected<std::vector<Line>> lines = Tokenize(text, name);
  if (!lines.ok()) return lines.error();
  if (lines->empty())
    return MakeError("corrupt", name +
                                    ": the file is empty; expected a Kinect v1 skeleton track "
                                    "(UTKinect joints_sXX_eYY.txt, MSR "
                                    "aXX_sYY_eZZ_skeleton3D.txt or UTD-MHAD skeleton.txt)");
  KinectTextVariant variant = options.variant;
  if (variant == KinectTextVariant::kDetect) {
    const Line& first = lines->front();
    switch (first.values.size()) {
      case kUtKinectNumbers:
        variant = KinectTextVariant::kUtKinect;
        break;
      case kRowNumbers:
        variant = KinectTextVariant::kMsrAction3d;
        break;
      case 2:
        variant = KinectTextVariant::kMsrDailyActivity3d;
        break;
      case kXyzNumbers:
        variant = KinectTextVariant::kUtdMhad;
        break;
      default:
        return Corrupt(name, first.number,
                       "has " + std::to_string(first.values.size()) +
                           " numbers; a Kinect v1 skeleton file has 61 (UTKinect: frame number "
                           "and 20 joints), 4 (MSR Action3D: one joint), 3 (UTD-MHAD: one "
                           "joint) or a 2-number header (MSR DailyActivity3D)");
    }
  }
  Expected<Parsed> parsed =
      variant == KinectTextVariant::kUtKinect      ? ParseUtKinect(*lines, name, options)
      : variant == KinectTextVariant::kMsrAction3d ? ParseMsrAction3d(*lines, name, options)
      : variant == KinectTextVariant::kUtdMhad     ? ParseUtdMhad(*lines, name, options)
                                                   : ParseMsrDaily(*lines, name, options);
  if (!parsed.ok()) return parsed.error();
  if (parsed->frames.empty())
    return MakeError("corrupt", name + ": no frame has a tracked skeleton (every joint is 0)");
  const size_t n = parsed->frames.size();
  std::string description = name + " (" + parsed->format + ", Kinect v1 20 joints -> 16; " +
                            std::to_string(n) + " frame" + (n == 1 ? "" : "s") +
                            " keyed by frame index" + parsed->notes + ")";
  return SkeletonTrack::Create(std::move(parsed->frames), std::move(description), options.lookup);
}

Expected<SkeletonTrack> ReadKinectV1SkeletonTrack(const std::string& path,
                                                  const KinectV1ReadOptions& options) {
  const auto text = ReadTextFile(path, "skeleton track file");
  if (!text.ok()) return text.error();
  return ParseKinectV1SkeletonText(*text, path, options);
}

}  // namespace reenact::capture
