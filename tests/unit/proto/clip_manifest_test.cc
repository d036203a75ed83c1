#include "proto/clip/manifest.h"

#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace reenact::proto {
namespace {

using nlohmann::json;

ClipManifest MakeManifest() {
  ClipManifest m;
  m.title = "Kata at the shrine";
  m.description = "Slow form, \"quoted\" and ünïcode";
  m.author = "naist";
  m.capture_time = "2024-02-29T23:59:60.125Z";
  m.location = {34.7325, 135.7336, 112.5, 4.0, 271.5};
  m.color_camera = {640, 480, 517.3, 516.5, 318.6, 255.3, {0.2624, -0.9531, -0.0054, 0.0026, 1.1633}};
  m.depth_camera = {320, 240, 285.0, 285.5, 160.25, 120.75, {}};
  m.depth_scale_m = 0.001;
  m.world_up = Eigen::Vector3d(0.6, -0.8, 0.0);
  for (int i = 0; i < kBodyPartCount; ++i) m.radius_ratio[i] = 0.1 + 0.05 * i;
  m.frame_count = 3;
  m.representative_frame = 2;
  m.frame_rate_hz = 30;
  m.map = {5000, "orb-256"};
  m.frame_parts = {{100, std::string(64, 'a')}, {200, std::string(64, 'b')}, {300, std::string(64, 'c')}};
  m.map_part = {4096, std::string(64, 'f')};
  m.flagged_skeleton_frames = {0, 2};
  return m;
}

void ExpectCameraEq(const PinholeCamera& a, const PinholeCamera& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.fx, b.fx);
  EXPECT_EQ(a.fy, b.fy);
  EXPECT_EQ(a.cx, b.cx);
  EXPECT_EQ(a.cy, b.cy);
  EXPECT_EQ(a.distortion.k1, b.distortion.k1);
  EXPECT_EQ(a.distortion.k2, b.distortion.k2);
  EXPECT_EQ(a.distortion.p1, b.distortion.p1);
  EXPECT_EQ(a.distortion.p2, b.distortion.p2);
  EXPECT_EQ(a.distortion.k3, b.distortion.k3);
}

TEST(ClipManifest, RoundTripKeepsEveryField) {
  const ClipManifest m = MakeManifest();
  const auto parsed = ParseManifest(SerializeManifest(m));
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  const ClipManifest& r = *parsed;
  EXPECT_EQ(r.title, m.title);
  EXPECT_EQ(r.description, m.description);
  EXPECT_EQ(r.author, m.author);
  EXPECT_EQ(r.capture_time, m.capture_time);
  EXPECT_EQ(r.location.lat_deg, 34.7325);
  EXPECT_EQ(r.location.lon_deg, 135.7336);
  EXPECT_EQ(r.location.alt_m, 112.5);
  EXPECT_EQ(r.location.accuracy_m, 4.0);
  ASSERT_TRUE(r.location.heading_deg.has_value());
  EXPECT_EQ(*r.location.heading_deg, 271.5);
  ExpectCameraEq(r.color_camera, m.color_camera);
  ExpectCameraEq(r.depth_camera, m.depth_camera);
  EXPECT_EQ(r.depth_scale_m, 0.001);
  EXPECT_EQ(r.world_up, m.world_up);
  EXPECT_EQ(r.radius_ratio, m.radius_ratio);
  EXPECT_EQ(r.representative_frame, 2);
  EXPECT_EQ(r.frame_count, 3);
  EXPECT_EQ(r.frame_rate_hz, 30);
  EXPECT_DOUBLE_EQ(r.DurationS(), 0.1);
  EXPECT_EQ(r.map.point_count, 5000);
  EXPECT_EQ(r.map.descriptor, "orb-256");
  ASSERT_EQ(r.frame_parts.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(r.frame_parts[i].bytes, m.frame_parts[i].bytes);
    EXPECT_EQ(r.frame_parts[i].sha256, m.frame_parts[i].sha256);
  }
  EXPECT_EQ(r.map_part.bytes, 4096u);
  EXPECT_EQ(r.map_part.sha256, m.map_part.sha256);
  EXPECT_EQ(r.flagged_skeleton_frames, m.flagged_skeleton_frames);
}

TEST(ClipManifest, WritesTheDocumentedLayout) {
  const json j = json::parse(SerializeManifest(MakeManifest()));
  EXPECT_EQ(j["format_version"], 1);
  EXPECT_EQ(j["skeleton"]["joints"].size(), 16u);
  EXPECT_EQ(j["skeleton"]["joints"][4], "l_shoulder");
  EXPECT_EQ(j["skeleton"]["parts"]["l_forearm"], json::array({"l_elbow", "l_hand"}));
  EXPECT_EQ(j["skeleton"]["parts"]["r_shin"], json::array({"r_knee", "r_foot"}));
  EXPECT_DOUBLE_EQ(j["radius_ratio"]["head"].get<double>(), 0.1);
  EXPECT_DOUBLE_EQ(j["duration_s"].get<double>(), 3.0 / 30.0);
  EXPECT_EQ(j["parts"]["frames"].size(), 3u);
}

TEST(ClipManifest, HeadingIsOptional) {
  ClipManifest m = MakeManifest();
  m.location.heading_deg.reset();
  const std::string text = SerializeManifest(m);
  EXPECT_FALSE(json::parse(text)["location"].contains("heading_deg"));
  const auto parsed = ParseManifest(text);
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  EXPECT_FALSE(parsed->location.heading_deg.has_value());
}

TEST(ClipManifest, FlaggedSkeletonFramesAreOptional) {
  // Manifests written before the field existed have none flagged.
  json j = json::parse(SerializeManifest(MakeManifest()));
  j.erase("flagged_skeleton_frames");
  const auto parsed = ParseManifest(j.dump());
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  EXPECT_TRUE(parsed->flagged_skeleton_frames.empty());
}

// Serialises the good manifest, lets `edit` break it, and returns the parse error.
template <typename Edit>
Error ParseEdited(Edit edit) {
  json j = json::parse(SerializeManifest(MakeManifest()));
  edit(j);
  const auto parsed = ParseManifest(j.dump());
  EXPECT_FALSE(parsed.ok());
  return parsed.ok() ? Error{} : parsed.error();
}

TEST(ClipManifest, RejectsLatitudeOutOfRange) {
  const Error e = ParseEdited([](json& j) { j["location"]["lat_deg"] = 95; });
  EXPECT_EQ(e.code, "invalid_argument");
  EXPECT_EQ(e.message, "manifest: location.lat_deg = 95 is outside [-90, 90]");
}

TEST(ClipManifest, RejectsLongitudeOutOfRange) {
  const Error e = ParseEdited([](json& j) { j["location"]["lon_deg"] = -180.5; });
  EXPECT_EQ(e.message, "manifest: location.lon_deg = -180.5 is outside [-180, 180]");
}

TEST(ClipManifest, RejectsHeadingOf360) {
  const Error e = ParseEdited([](json& j) { j["location"]["heading_deg"] = 360; });
  EXPECT_NE(e.message.find("location.heading_deg = 360 is outside [0, 360)"), std::string::npos)
      << e.message;
}

TEST(ClipManifest, RejectsMissingField) {
  const Error e = ParseEdited([](json& j) { j["color_camera"].erase("fx"); });
  EXPECT_EQ(e.message, "manifest: missing field color_camera.fx");
}

TEST(ClipManifest, RejectsWrongType) {
  const Error e = ParseEdited([](json& j) { j["title"] = 7; });
  EXPECT_EQ(e.message, "manifest: title must be a string");
}

TEST(ClipManifest, RejectsNonPositiveFocalLength) {
  const Error e = ParseEdited([](json& j) { j["depth_camera"]["fy"] = 0; });
  EXPECT_EQ(e.message, "manifest: depth_camera.fy = 0 is outside (0, inf)");
}

TEST(ClipManifest, RejectsFractionalImageWidth) {
  const Error e = ParseEdited([](json& j) { j["color_camera"]["width"] = 640.5; });
  EXPECT_EQ(e.message, "manifest: color_camera.width must be an integer");
}

TEST(ClipManifest, RejectsFrameCountDisagreeingWithParts) {
  const Error e = ParseEdited([](json& j) { j["frame_count"] = 4; });
  EXPECT_EQ(e.message, "manifest: frame_count = 4 but parts.frames lists 3 frames");
}

TEST(ClipManifest, RejectsZeroFrames) {
  const Error e = ParseEdited([](json& j) {
    j["frame_count"] = 0;
    j["parts"]["frames"] = json::array();
  });
  EXPECT_EQ(e.message, "manifest: frame_count = 0 is outside [1, 2147483647]");
}

TEST(ClipManifest, RejectsRepresentativeFrameOutOfRange) {
  const Error e = ParseEdited([](json& j) { j["representative_frame"] = 3; });
  EXPECT_EQ(e.message, "manifest: representative_frame = 3 is outside [0, 2]");
}

TEST(ClipManifest, RejectsFlaggedFrameOutOfRange) {
  const Error e = ParseEdited([](json& j) { j["flagged_skeleton_frames"] = {0, 3}; });
  EXPECT_NE(e.message.find("flagged_skeleton_frames[1] = 3 is outside [0, 2]"), std::string::npos)
      << e.message;
}

TEST(ClipManifest, RejectsFlaggedFramesOutOfOrder) {
  const Error e = ParseEdited([](json& j) { j["flagged_skeleton_frames"] = {2, 2}; });
  EXPECT_NE(e.message.find("flagged_skeleton_frames[1] = 2 is not above"), std::string::npos)
      << e.message;
}

TEST(ClipManifest, RejectsRadiusRatioOutOfRange) {
  EXPECT_EQ(ParseEdited([](json& j) { j["radius_ratio"]["l_thigh"] = 0; }).message,
            "manifest: radius_ratio.l_thigh = 0 is outside (0, 2]");
  EXPECT_EQ(ParseEdited([](json& j) { j["radius_ratio"]["head"] = 2.5; }).message,
            "manifest: radius_ratio.head = 2.5 is outside (0, 2]");
}

TEST(ClipManifest, RejectsUnknownRadiusRatioPart) {
  const Error e = ParseEdited([](json& j) { j["radius_ratio"]["tail"] = 0.1; });
  EXPECT_EQ(e.message, "manifest: radius_ratio names unknown part \"tail\"");
}

TEST(ClipManifest, RejectsUppercaseSha256) {
  const Error e = ParseEdited([](json& j) { j["parts"]["frames"][1]["sha256"] = std::string(64, 'B'); });
  EXPECT_EQ(e.message, "manifest: parts.frames[1].sha256 must be 64 lowercase hexadecimal digits");
}

TEST(ClipManifest, RejectsShortSha256) {
  const Error e = ParseEdited([](json& j) { j["parts"]["map"]["sha256"] = "abc"; });
  EXPECT_EQ(e.message, "manifest: parts.map.sha256 must be 64 lowercase hexadecimal digits");
}

TEST(ClipManifest, RejectsZeroSizedPart) {
  const Error e = ParseEdited([](json& j) { j["parts"]["frames"][0]["bytes"] = 0; });
  EXPECT_EQ(e.message.rfind("manifest: parts.frames[0].bytes = 0 is outside [1, ", 0), 0u) << e.message;
}

TEST(ClipManifest, RejectsNonUnitWorldUp) {
  const Error e = ParseEdited([](json& j) { j["world_up"] = json::array({0, -2, 0}); });
  EXPECT_EQ(e.message, "manifest: world_up has length 2 but must be a unit vector (within 1e-3)");
}

TEST(ClipManifest, AcceptsWorldUpWithinTolerance) {
  json j = json::parse(SerializeManifest(MakeManifest()));
  j["world_up"] = json::array({0, -1.0005, 0});
  EXPECT_TRUE(ParseManifest(j.dump()).ok());
}

TEST(ClipManifest, RejectsUnknownFormatVersion) {
  const Error e = ParseEdited([](json& j) { j["format_version"] = 2; });
  EXPECT_EQ(e.code, "unsupported");
  EXPECT_NE(e.message.find("format_version 2 is not supported"), std::string::npos);
}

TEST(ClipManifest, RejectsWrongJointName) {
  const Error e = ParseEdited([](json& j) { j["skeleton"]["joints"][4] = "l_shouldr"; });
  EXPECT_EQ(e.message,
            "manifest: skeleton.joints[4] = \"l_shouldr\" but this build expects \"l_shoulder\"");
}

TEST(ClipManifest, RejectsWrongPartJoints) {
  const Error e = ParseEdited([](json& j) {
    j["skeleton"]["parts"]["l_forearm"] = json::array({"l_elbow", "r_hand"});
  });
  EXPECT_NE(e.message.find("skeleton.parts.l_forearm"), std::string::npos) << e.message;
}

TEST(ClipManifest, RejectsMissingJoint) {
  const Error e = ParseEdited([](json& j) { j["skeleton"]["joints"].erase(15); });
  EXPECT_EQ(e.message, "manifest: skeleton.joints must have 16 elements, not 15");
}

TEST(ClipManifest, RejectsBadCaptureTime) {
  const Error e = ParseEdited([](json& j) { j["capture_time"] = "2023-02-29T10:00:00Z"; });
  EXPECT_NE(e.message.find("capture_time = \"2023-02-29T10:00:00Z\" is not an ISO 8601"),
            std::string::npos);
}

TEST(ClipManifest, RejectsInconsistentDuration) {
  const Error e = ParseEdited([](json& j) { j["duration_s"] = 5; });
  EXPECT_NE(e.message.find("duration_s = 5 but frame_count / frame_rate_hz"), std::string::npos);
}

TEST(ClipManifest, RejectsUnknownDescriptor) {
  const Error e = ParseEdited([](json& j) { j["map"]["descriptor"] = "sift-128"; });
  EXPECT_NE(e.message.find("map.descriptor = \"sift-128\""), std::string::npos);
}

TEST(ClipManifest, RejectsNonPositiveDepthScale) {
  const Error e = ParseEdited([](json& j) { j["depth_scale_m"] = -0.001; });
  EXPECT_EQ(e.message, "manifest: depth_scale_m = -0.001 is outside (0, 1]");
}

TEST(ClipManifest, RejectsInvalidJson) {
  const auto parsed = ParseManifest("{\"format_version\": 1,");
  ASSERT_FALSE(parsed.ok());
  EXPECT_EQ(parsed.error().code, "invalid_argument");
  EXPECT_NE(parsed.error().message.find("not valid JSON"), std::string::npos);
}

// The good manifest's text with `from` (which must occur once) replaced by `to`.
std::string EditedText(const std::string& from, const std::string& to) {
  std::string text = SerializeManifest(MakeManifest());
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

TEST(ClipManifest, RejectsAKeyRepeatedInOneObject) {
  // nlohmann alone would keep the last value and accept each of these.
  const struct {
    std::string from, to, key;
  } cases[] = {
      {"\"title\": \"Kata at the shrine\"",
       "\"title\": \"Kata at the shrine\", \"title\": \"Other\"", "title"},
      {"\"lat_deg\": 34.7325", "\"lat_deg\": 34.7325, \"lat_deg\": 34.7325",
       "location.lat_deg"},
      {"\"bytes\": 200", "\"bytes\": 200, \"bytes\": 200", "parts.frames[1].bytes"},
  };
  for (const auto& c : cases) {
    const auto parsed = ParseManifest(EditedText(c.from, c.to));
    ASSERT_FALSE(parsed.ok()) << c.key;
    EXPECT_EQ(parsed.error().code, "invalid_argument");
    EXPECT_EQ(parsed.error().message,
              "manifest: key " + c.key +
                  " appears more than once in the same object; keys in a JSON object must be "
                  "unique");
  }
  // The same key in sibling objects (every frame has "bytes" and "sha256") is the normal case.
  EXPECT_TRUE(ParseManifest(EditedText("\"bytes\": 200", "\"bytes\": 200")).ok());
}

TEST(ClipManifest, RejectsNonObjectDocument) {
  const auto parsed = ParseManifest("[1, 2]");
  ASSERT_FALSE(parsed.ok());
  EXPECT_EQ(parsed.error().message, "manifest: document must be an object");
}

TEST(ClipManifest, ValidatesIso8601Times) {
  EXPECT_TRUE(IsIso8601Utc("2024-05-01T12:34:56Z"));
  EXPECT_TRUE(IsIso8601Utc("2000-02-29T00:00:00.5Z"));
  EXPECT_FALSE(IsIso8601Utc("1900-02-29T00:00:00Z"));  // not a leap year
  EXPECT_FALSE(IsIso8601Utc("2024-05-01T12:34:56"));   // no zone
  EXPECT_FALSE(IsIso8601Utc("2024-05-01T12:34:56+09:00"));
  EXPECT_FALSE(IsIso8601Utc("2024-13-01T12:34:56Z"));
  EXPECT_FALSE(IsIso8601Utc("2024-04-31T12:34:56Z"));
  EXPECT_FALSE(IsIso8601Utc("2024-05-01T24:00:00Z"));
  EXPECT_FALSE(IsIso8601Utc("2024-05-01T12:34:56.Z"));
}

}  // namespace
}  // namespace reenact::proto
