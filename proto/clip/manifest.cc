#include "proto/clip/manifest.h"

#include <cctype>
#include <cmath>
#include <nlohmann/json.hpp>

#include "proto/clip/content_hash.h"
#include "proto/clip/json_fields.h"
#include "proto/clip/json_unique_keys.h"

namespace reenact::proto {
namespace {

using internal::Interval;
using internal::JsonField;
using internal::JsonFieldError;
using nlohmann::json;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int64_t kMaxImageSide = 1 << 16;

json CameraToJson(const PinholeCamera& c) {
  return json{{"width", c.width},
              {"height", c.height},
              {"fx", c.fx},
              {"fy", c.fy},
              {"cx", c.cx},
              {"cy", c.cy},
              {"distortion",
               {{"k1", c.distortion.k1},
                {"k2", c.distortion.k2},
                {"p1", c.distortion.p1},
                {"p2", c.distortion.p2},
                {"k3", c.distortion.k3}}}};
}

json PartToJson(const PartInfo& p) { return json{{"bytes", p.bytes}, {"sha256", p.sha256}}; }

PinholeCamera CameraFromJson(const JsonField& f) {
  PinholeCamera c;
  c.width = static_cast<int>(f["width"].IntegerIn(1, kMaxImageSide));
  c.height = static_cast<int>(f["height"].IntegerIn(1, kMaxImageSide));
  const Interval positive{0, kInf, true, true};
  c.fx = f["fx"].NumberIn(positive);
  c.fy = f["fy"].NumberIn(positive);
  c.cx = f["cx"].Number();
  c.cy = f["cy"].Number();
  const JsonField d = f["distortion"];
  c.distortion.k1 = d["k1"].Number();
  c.distortion.k2 = d["k2"].Number();
  c.distortion.p1 = d["p1"].Number();
  c.distortion.p2 = d["p2"].Number();
  c.distortion.k3 = d["k3"].Number();
  return c;
}

PartInfo PartFromJson(const JsonField& f) {
  PartInfo p;
  p.bytes = static_cast<uint64_t>(f["bytes"].IntegerIn(1, INT64_MAX));
  const JsonField sha = f["sha256"];
  p.sha256 = sha.String();
  if (!IsSha256Hex(p.sha256)) sha.Fail("must be 64 lowercase hexadecimal digits");
  return p;
}

std::string LimitedString(const JsonField& f, size_t max_bytes) {
  std::string s = f.String();
  if (s.size() > max_bytes) f.Fail("is longer than " + std::to_string(max_bytes) + " bytes");
  return s;
}

void CheckSkeletonDefinition(const JsonField& f) {
  const JsonField joints = f["joints"];
  joints.ExpectArray(kJointCount);
  for (int i = 0; i < kJointCount; ++i) {
    const std::string name = joints[static_cast<size_t>(i)].String();
    const std::string_view expected = JointName(static_cast<Joint>(i));
    if (name != expected)
      joints[static_cast<size_t>(i)].Fail("= \"" + name + "\" but this build expects \"" +
                                          std::string(expected) + "\"");
  }
  const JsonField parts = f["parts"];
  parts.ExpectObject();
  if (parts.json().size() != static_cast<size_t>(kBodyPartCount))
    parts.Fail("must name exactly " + std::to_string(kBodyPartCount) + " parts");
  for (const auto& [name, value] : parts.json().items()) {
    if (!PartFromName(name)) parts.Fail("names unknown part \"" + name + "\"");
  }
  for (int i = 0; i < kBodyPartCount; ++i) {
    const auto part = static_cast<BodyPart>(i);
    const JsonField pair = parts[PartName(part)];
    pair.ExpectArray(2);
    const auto [a, b] = PartJoints(part);
    const std::string ja = pair[0].String(), jb = pair[1].String();
    if (ja != JointName(a) || jb != JointName(b))
      pair.Fail("= [\"" + ja + "\", \"" + jb + "\"] but this build expects [\"" +
                std::string(JointName(a)) + "\", \"" + std::string(JointName(b)) + "\"]");
  }
}

// Title, description, author and capture time.
void ReadDescription(const JsonField& root, ClipManifest& m) {
  m.title = LimitedString(root["title"], kMaxManifestNameBytes);
  m.description = LimitedString(root["description"], kMaxManifestDescriptionBytes);
  m.author = LimitedString(root["author"], kMaxManifestNameBytes);
  const JsonField time = root["capture_time"];
  m.capture_time = time.String();
  if (!IsIso8601Utc(m.capture_time))
    time.Fail("= \"" + m.capture_time + "\" is not an ISO 8601 UTC time like 2024-05-01T12:34:56Z");
}

ClipLocation LocationFromJson(const JsonField& loc) {
  ClipLocation location;
  location.lat_deg = loc["lat_deg"].NumberIn({-90, 90});
  location.lon_deg = loc["lon_deg"].NumberIn({-180, 180});
  location.alt_m = loc["alt_m"].Number();
  location.accuracy_m = loc["accuracy_m"].NumberIn({0, kInf, false, true});
  if (loc.Has("heading_deg") && !loc.json()["heading_deg"].is_null())
    location.heading_deg = loc["heading_deg"].NumberIn({0, 360, false, true});
  return location;
}

Eigen::Vector3d WorldUpFromJson(const JsonField& up) {
  up.ExpectArray(3);
  Eigen::Vector3d world_up;
  for (int i = 0; i < 3; ++i) world_up[i] = up[static_cast<size_t>(i)].Number();
  if (std::abs(world_up.norm() - 1.0) > 1e-3)
    up.Fail("has length " + internal::FormatNumber(world_up.norm()) +
            " but must be a unit vector (within 1e-3)");
  return world_up;
}

std::array<double, kBodyPartCount> RadiusRatiosFromJson(const JsonField& ratios) {
  ratios.ExpectObject();
  for (const auto& [name, value] : ratios.json().items())
    if (!PartFromName(name)) ratios.Fail("names unknown part \"" + name + "\"");
  std::array<double, kBodyPartCount> radius_ratio{};
  for (int i = 0; i < kBodyPartCount; ++i)
    radius_ratio[i] = ratios[PartName(static_cast<BodyPart>(i))].NumberIn({0, 2, true, false});
  return radius_ratio;
}

// Frame count (that of the frame parts listed), representative frame and frame rate, checked
// against duration_s when given.
void ReadFrameTiming(const JsonField& root, size_t frame_parts, ClipManifest& m) {
  m.frame_count = root["frame_count"].IntegerIn(1, INT32_MAX);
  if (static_cast<size_t>(m.frame_count) != frame_parts)
    root["frame_count"].Fail("= " + std::to_string(m.frame_count) + " but parts.frames lists " +
                             std::to_string(frame_parts) + " frames");
  m.representative_frame = root["representative_frame"].IntegerIn(0, m.frame_count - 1);
  m.frame_rate_hz = root["frame_rate_hz"].NumberIn({0, 1000, true, false});
  if (root.Has("duration_s")) {
    const double duration = root["duration_s"].Number();
    if (std::abs(duration - m.DurationS()) > 1e-6 * std::max(1.0, m.DurationS()))
      root["duration_s"].Fail(
          "= " + internal::FormatNumber(duration) +
          " but frame_count / frame_rate_hz = " + internal::FormatNumber(m.DurationS()));
  }
}

MapSummary MapFromJson(const JsonField& map) {
  MapSummary summary;
  summary.point_count = map["point_count"].IntegerIn(0, INT32_MAX);
  summary.descriptor = map["descriptor"].String();
  if (summary.descriptor != kMapDescriptorOrb256)
    map["descriptor"].Fail("= \"" + summary.descriptor + "\" is not a known descriptor (\"" +
                           std::string(kMapDescriptorOrb256) + "\")");
  return summary;
}

std::vector<int64_t> FlaggedFramesFromJson(const JsonField& flagged, int64_t frame_count) {
  std::vector<int64_t> frames;
  const size_t count = flagged.ExpectArray();
  for (size_t i = 0; i < count; ++i) {
    const int64_t n = flagged[i].IntegerIn(0, frame_count - 1);
    if (!frames.empty() && n <= frames.back())
      flagged[i].Fail("= " + std::to_string(n) +
                      " is not above the entry before it (the list "
                      "must be ascending without repeats)");
    frames.push_back(n);
  }
  return frames;
}

ClipManifest ManifestFromJson(const json& document) {
  const JsonField root(document, "manifest");
  root.ExpectObject();
  const int64_t version = root["format_version"].Integer();
  if (version != kManifestFormatVersion)
    throw Error{"unsupported", "manifest: format_version " + std::to_string(version) +
                                   " is not supported (this build reads version " +
                                   std::to_string(kManifestFormatVersion) + ")"};

  ClipManifest m;
  ReadDescription(root, m);
  m.location = LocationFromJson(root["location"]);
  m.color_camera = CameraFromJson(root["color_camera"]);
  m.depth_camera = CameraFromJson(root["depth_camera"]);
  m.depth_scale_m = root["depth_scale_m"].NumberIn({0, 1, true, false});
  m.world_up = WorldUpFromJson(root["world_up"]);
  CheckSkeletonDefinition(root["skeleton"]);
  m.radius_ratio = RadiusRatiosFromJson(root["radius_ratio"]);

  const JsonField parts = root["parts"];
  const JsonField frames = parts["frames"];
  const size_t frame_parts = frames.ExpectArray();
  ReadFrameTiming(root, frame_parts, m);
  m.map = MapFromJson(root["map"]);
  if (root.Has("flagged_skeleton_frames"))
    m.flagged_skeleton_frames =
        FlaggedFramesFromJson(root["flagged_skeleton_frames"], m.frame_count);

  m.frame_parts.reserve(frame_parts);
  for (size_t i = 0; i < frame_parts; ++i) m.frame_parts.push_back(PartFromJson(frames[i]));
  m.map_part = PartFromJson(parts["map"]);
  return m;
}

bool AllDigits(std::string_view s) {
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return !s.empty();
}

int ToInt(std::string_view s) {
  int v = 0;
  for (char c : s) v = v * 10 + (c - '0');
  return v;
}

}  // namespace

bool IsIso8601Utc(std::string_view t) {
  // YYYY-MM-DDTHH:MM:SS, then optional .fraction, then Z.
  if (t.size() < 20 || t.back() != 'Z') return false;
  if (t[4] != '-' || t[7] != '-' || t[10] != 'T' || t[13] != ':' || t[16] != ':') return false;
  const std::string_view year = t.substr(0, 4), month = t.substr(5, 2), day = t.substr(8, 2),
                         hour = t.substr(11, 2), minute = t.substr(14, 2), second = t.substr(17, 2);
  for (std::string_view part : {year, month, day, hour, minute, second})
    if (!AllDigits(part)) return false;
  const std::string_view rest = t.substr(19, t.size() - 20);
  if (!rest.empty() && (rest[0] != '.' || !AllDigits(rest.substr(1)))) return false;
  const int y = ToInt(year), mo = ToInt(month), d = ToInt(day);
  if (mo < 1 || mo > 12 || d < 1) return false;
  static constexpr int kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  const bool leap = (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
  const int days = kDays[mo - 1] + (mo == 2 && leap ? 1 : 0);
  return d <= days && ToInt(hour) <= 23 && ToInt(minute) <= 59 && ToInt(second) <= 60;
}

std::string SerializeManifest(const ClipManifest& m) {
  json location{{"lat_deg", m.location.lat_deg},
                {"lon_deg", m.location.lon_deg},
                {"alt_m", m.location.alt_m},
                {"accuracy_m", m.location.accuracy_m}};
  if (m.location.heading_deg) location["heading_deg"] = *m.location.heading_deg;

  json joints = json::array();
  for (int i = 0; i < kJointCount; ++i) joints.push_back(JointName(static_cast<Joint>(i)));
  json parts = json::object();
  json ratios = json::object();
  for (int i = 0; i < kBodyPartCount; ++i) {
    const auto part = static_cast<BodyPart>(i);
    const auto [a, b] = PartJoints(part);
    parts[std::string(PartName(part))] = json::array({JointName(a), JointName(b)});
    ratios[std::string(PartName(part))] = m.radius_ratio[i];
  }
  json frames = json::array();
  for (const PartInfo& p : m.frame_parts) frames.push_back(PartToJson(p));

  const json document{
      {"format_version", kManifestFormatVersion},
      {"title", m.title},
      {"description", m.description},
      {"author", m.author},
      {"capture_time", m.capture_time},
      {"location", location},
      {"color_camera", CameraToJson(m.color_camera)},
      {"depth_camera", CameraToJson(m.depth_camera)},
      {"depth_scale_m", m.depth_scale_m},
      {"world_up", json::array({m.world_up.x(), m.world_up.y(), m.world_up.z()})},
      {"skeleton", {{"joints", joints}, {"parts", parts}}},
      {"radius_ratio", ratios},
      {"representative_frame", m.representative_frame},
      {"frame_count", m.frame_count},
      {"frame_rate_hz", m.frame_rate_hz},
      {"duration_s", m.DurationS()},
      {"map", {{"point_count", m.map.point_count}, {"descriptor", m.map.descriptor}}},
      {"flagged_skeleton_frames", m.flagged_skeleton_frames},
      {"parts", {{"frames", frames}, {"map", PartToJson(m.map_part)}}},
  };
  return document.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

Expected<ClipManifest> ParseManifest(std::string_view text) {
  const json document = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (document.is_discarded())
    return MakeError("invalid_argument", "manifest: not valid JSON (or not UTF-8)");
  if (const auto duplicate = FirstDuplicateKey(text)) {
    return MakeError("invalid_argument",
                     "manifest: key " + *duplicate +
                         " appears more than once in the same object; keys in a JSON object "
                         "must be unique");
  }
  try {
    return ManifestFromJson(document);
  } catch (const JsonFieldError& e) {
    return MakeError("invalid_argument", e.what());
  } catch (const Error& e) {
    return e;
  }
}

}  // namespace reenact::proto
