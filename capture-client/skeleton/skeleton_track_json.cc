#include "capture-client/skeleton/skeleton_track_json.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <system_error>

#include "common/io/text_file.h"

namespace reenact::capture {
namespace {

using nlohmann::json;

// A validation failure inside the parser; turned into an Error at its boundary.
struct Invalid : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string Number(double v) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), v);
  return std::string(buffer, result.ptr);
}

// A JSON value with its path in the document ("frames[3].joints.head"), for messages.
struct Field {
  const json& value;
  std::string path;

  [[noreturn]] void Fail(const std::string& what) const { throw Invalid(path + " " + what); }

  bool Has(const std::string& key) const { return value.is_object() && value.contains(key); }
  Field operator[](const std::string& key) const {
    if (!value.is_object()) Fail("must be an object");
    const auto it = value.find(key);
    const std::string child = path.empty() ? key : path + "." + key;
    if (it == value.end()) throw Invalid("missing field " + child);
    return Field{*it, child};
  }
  Field At(size_t i) const { return Field{value[i], path + "[" + std::to_string(i) + "]"}; }

  void ExpectObject() const {
    if (!value.is_object()) Fail("must be an object");
  }
  size_t ExpectArray() const {
    if (!value.is_array()) Fail("must be an array");
    return value.size();
  }
  double FiniteNumber() const {
    if (!value.is_number()) Fail("must be a number");
    const double v = value.get<double>();
    if (!std::isfinite(v)) Fail("must be a finite number");
    return v;
  }
  int64_t NonNegativeInteger() const {
    if (value.is_number_unsigned()) {
      const uint64_t u = value.get<uint64_t>();
      if (u > static_cast<uint64_t>(INT64_MAX)) Fail("= " + std::to_string(u) + " is too large");
      return static_cast<int64_t>(u);
    }
    if (!value.is_number_integer()) Fail("must be an integer");
    const int64_t v = value.get<int64_t>();
    if (v < 0) Fail("= " + std::to_string(v) + " must be >= 0");
    return v;
  }
  std::string String() const {
    if (!value.is_string()) Fail("must be a string");
    return value.get<std::string>();
  }
};

SkeletonTrackFrame ParseFrame(const Field& frame) {
  frame.ExpectObject();
  SkeletonTrackFrame out;
  if (frame.Has("timestamp_s")) out.timestamp_s = frame["timestamp_s"].FiniteNumber();
  if (frame.Has("frame_index")) out.frame_index = frame["frame_index"].NonNegativeInteger();
  if (!out.timestamp_s && !out.frame_index)
    frame.Fail("has neither timestamp_s nor frame_index; a frame needs at least one");
  const Field joints = frame["joints"];
  joints.ExpectObject();
  for (const auto& [name, value] : joints.value.items()) {
    const Field joint{value, joints.path + "." + name};
    const std::optional<Joint> id = JointFromName(name);
    if (!id)
      joint.Fail(
          "is not one of our joints (head, neck, torso, waist, l_shoulder, l_elbow, "
          "l_hand, r_shoulder, r_elbow, r_hand, l_hip, l_knee, l_foot, r_hip, r_knee, "
          "r_foot)");
    joint.ExpectObject();
    const Field position = joint["position"];
    if (position.ExpectArray() != 3)
      position.Fail("must have 3 elements [x, y, z], not " + std::to_string(position.value.size()));
    Eigen::Vector3d p;
    for (size_t k = 0; k < 3; ++k) p[static_cast<int>(k)] = position.At(k).FiniteNumber();
    const Field confidence = joint["confidence"];
    const double c = confidence.FiniteNumber();
    if (!(c >= 0 && c <= 1)) confidence.Fail("= " + Number(c) + " is outside [0, 1]");
    out.skeleton_in_sensor.position[Index(*id)] = p;
    out.skeleton_in_sensor.confidence[Index(*id)] = c;
  }
  return out;
}

// The frame-to-frame rules, with the field named (SkeletonTrack::Create checks them again,
// with frame numbers only).
void CheckOrder(const std::vector<SkeletonTrackFrame>& frames, size_t i) {
  const std::string where = "frames[" + std::to_string(i) + "]";
  const SkeletonTrackFrame& f = frames[i];
  const bool timed = frames.front().timestamp_s.has_value();
  if (f.timestamp_s.has_value() != timed)
    throw Invalid(where +
                  (timed ? " has no timestamp_s while frames[0] has one"
                         : " has a timestamp_s while frames[0] has none") +
                  "; give every frame a timestamp or none");
  if (i == 0) return;
  const SkeletonTrackFrame& previous = frames[i - 1];
  if (f.timestamp_s && *f.timestamp_s <= *previous.timestamp_s)
    throw Invalid(where + ".timestamp_s = " + Number(*f.timestamp_s) + " is " +
                  (*f.timestamp_s == *previous.timestamp_s ? "the same as" : "before") +
                  " the previous frame's " + Number(*previous.timestamp_s) +
                  "; timestamps must increase strictly (a duplicate frame?)");
  if (!f.frame_index) return;
  for (size_t k = i; k-- > 0;) {
    if (!frames[k].frame_index) continue;
    if (*f.frame_index <= *frames[k].frame_index)
      throw Invalid(where + ".frame_index = " + std::to_string(*f.frame_index) + " is not after " +
                    "frames[" + std::to_string(k) +
                    "].frame_index = " + std::to_string(*frames[k].frame_index) +
                    "; frame indices must increase strictly (a duplicate frame?)");
    return;
  }
}

}  // namespace

Expected<SkeletonTrack> ParseSkeletonTrackJson(std::string_view text, const std::string& name,
                                               const SkeletonTrackLookupOptions& options) {
  json document;
  try {
    document = json::parse(text);
  } catch (const json::exception& e) {  // parse_error, or out_of_range for 1e999
    return MakeError("corrupt", name + ": not valid JSON (" + e.what() +
                                    "); expected a reenact-skeleton-track document");
  }
  std::vector<SkeletonTrackFrame> frames;
  std::string description = name;
  try {
    const Field root{document, ""};
    if (!document.is_object()) root.Fail("must be a JSON object");
    const std::string format = root["format"].String();
    if (format != kSkeletonTrackFormat)
      root["format"].Fail("= \"" + format + "\" is not \"" + std::string(kSkeletonTrackFormat) +
                          "\"");
    const Field version = root["version"];
    if (!version.value.is_number_integer()) version.Fail("must be an integer");
    if (version.value.get<int64_t>() != kSkeletonTrackVersion)
      return MakeError("unsupported", name + ": skeleton track version " +
                                          std::to_string(version.value.get<int64_t>()) +
                                          " is not supported; this build reads version " +
                                          std::to_string(kSkeletonTrackVersion) +
                                          " (update reenact)");
    const std::string frame_name = root["frame"].String();
    if (frame_name != "sensor")
      root["frame"].Fail("= \"" + frame_name +
                         "\" is not supported; a track must be in the \"sensor\" frame");
    if (root.Has("description")) description += ": " + root["description"].String();
    const Field list = root["frames"];
    const size_t n = list.ExpectArray();
    frames.reserve(n);
    for (size_t i = 0; i < n; ++i) {
      frames.push_back(ParseFrame(list.At(i)));
      CheckOrder(frames, i);
    }
    if (frames.empty()) list.Fail("is empty; a track needs at least one frame");
  } catch (const Invalid& e) {
    return MakeError("corrupt", name + ": " + e.what());
  }
  return SkeletonTrack::Create(std::move(frames), std::move(description), options);
}

Expected<SkeletonTrack> ReadSkeletonTrackJson(const std::string& path,
                                              const SkeletonTrackLookupOptions& options) {
  const auto text = ReadTextFile(path, "skeleton track file");
  if (!text.ok()) return text.error();
  return ParseSkeletonTrackJson(*text, path, options);
}

std::string SkeletonTrackToJson(const SkeletonTrack& track) {
  json frames = json::array();
  for (const SkeletonTrackFrame& f : track.frames()) {
    json frame = json::object();
    if (f.timestamp_s) frame["timestamp_s"] = *f.timestamp_s;
    if (f.frame_index) frame["frame_index"] = *f.frame_index;
    json joints = json::object();
    for (int j = 0; j < kJointCount; ++j) {
      const Joint joint = static_cast<Joint>(j);
      if (!f.skeleton_in_sensor.Has(joint)) continue;
      const Eigen::Vector3d& p = f.skeleton_in_sensor[joint];
      joints[std::string(JointName(joint))] = {{"position", {p.x(), p.y(), p.z()}},
                                               {"confidence", f.skeleton_in_sensor.confidence[j]}};
    }
    frame["joints"] = std::move(joints);
    frames.push_back(std::move(frame));
  }
  const json document{{"format", kSkeletonTrackFormat},
                      {"version", kSkeletonTrackVersion},
                      {"frame", "sensor"},
                      {"description", track.description()},
                      {"frames", std::move(frames)}};
  return document.dump(1, ' ', false, json::error_handler_t::replace) + "\n";
}

Status WriteSkeletonTrackJson(const SkeletonTrack& track, const std::string& path) {
  const std::string temporary = path + ".partial";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) return MakeError("io", path + ": cannot create " + temporary);
    out << SkeletonTrackToJson(track);
    out.flush();
    if (!out) {
      std::remove(temporary.c_str());
      return MakeError("io", path + ": cannot write the file (disk full?)");
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::remove(temporary.c_str());
    return MakeError("io", path + ": cannot rename " + temporary + " into place: " + ec.message());
  }
  return {};
}

}  // namespace reenact::capture
