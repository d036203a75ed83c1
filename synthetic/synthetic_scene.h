#pragma once
// A deterministic synthetic RGB-D capture: a textured, articulated person, either the
// procedural body (body_model.h, body_mesh.h, body_texture.h; the default, needs no data
// file) or a glTF skinned mesh (skinned_body.h, e.g. ../shared/data/models/CesiumMan.glb;
// see SyntheticBodySpec), performing a scripted motion (scenario.h) in
// a textured room (room.h), seen by a Kinect-like sensor (PinholeCamera::KinectLike(),
// 640x480), static about 3 m in front of the subject at 1.3 m height, static 0.9 m in front
// at 1.25 m (upper-body-turn's close-up) or hand-held, as the scenario says (its
// world_from_sensor per frame).
// Ground truth for tests and evaluation: the skeleton, the sensor pose, per-pixel depth,
// the subject mask and body-part labels.
//
// World frame: z up, floor at z = 0, metres; the subject stands near the origin and at
// frame 0 faces the sensor (world -y). Rendering uses common/render/rasterizer.h.

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "common/error/expected.h"
#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "common/skeleton/skeleton.h"
#include "synthetic/depth_noise.h"
#include "synthetic/room.h"

namespace reenact::capture {

struct SyntheticView {
  ImageRgb8 color;          // sRGB, 3 channels
  ImageDepthMm depth;       // camera z in millimetres; 0 where nothing is hit or out of range
  ImageGray8 mask;          // 255 where the subject is visible, else 0
  ImageLabel8 part_labels;  // PartLabel(part) of the visible subject pixel, else 0
};

struct SyntheticRenderOptions {
  // Draw the room (walls, floor, ceiling, furniture). Off: background colour 0, depth 0.
  bool draw_room = true;
  // Draw the subject. Off: the empty room, as a viewer visiting later sees it (mask, labels 0).
  bool draw_subject = true;
  // Kinect-like depth errors (depth_noise.h: projector shadow holes at silhouettes, noise,
  // disparity quantisation) as `noise` says, seeded by the scene's seed and the frame
  // index. Mask and labels stay exact.
  bool depth_noise = false;
  // Depth readings outside [min_depth_m, max_depth_m] become 0 (no reading), as on a
  // Kinect. Defaults 0.4 m and 8 m; 0 <= min < max <= 65.5.
  double min_depth_m = 0.4;
  double max_depth_m = 8.0;
  // The depth error model's options, used when depth_noise is on.
  DepthNoiseOptions noise{};

  // Throws CheckError when a field is out of range.
  void Check() const;
};

// Which subject a scene shows.
//  - procedural (gltf_path empty, the default): the procedural body; it plays scenarios
//    given as poses (turn-and-kick, upper-body-turn, walk-handheld, calibration) and bvh:
//    motion, retargeted by bone directions onto its own dimensions
//    (body_pose_from_skeleton.h); not model-walk.
//  - skinned (gltf_path set): the glTF skinned mesh at that path (.glb or .gltf), scaled to
//    height_m (0 keeps the model's own; CesiumMan 1.51 m). It plays every scenario: poses
//    are retargeted onto it from the procedural body's skeleton (PoseBody), bvh: motion from
//    its target skeletons, model-walk is the model's own animation. The ground-truth
//    skeleton comes from its skin joints (skinned_body.h says how).
struct SyntheticBodySpec {
  std::string gltf_path;
  double height_m = 0;
  // The subject's lighting: the ambient share of its Lambert shading (room.h), in [0, 1].
  // kSceneAmbient: lit by the scene's directional light, so a surface is as bright as it
  // faces the light at that frame; 1: lit flat, its albedo as it is from every side (no
  // shading for image-based texturing to carry from one pose to another). The room keeps
  // the scene's light.
  double ambient = kSceneAmbient;

  bool skinned() const { return !gltf_path.empty(); }
};

class SyntheticScene {
 public:
  // A scene playing the named scenario (see ScenarioNames()) on the given body; seed drives
  // the depth noise (and walk-handheld's hand shake). Errors: "not_found" listing the known
  // scenarios for an unknown name; "unsupported" for model-walk (the model's own
  // animation) on the procedural body or on a model without animation;
  // the errors of SkinnedBody::Load for a body file that cannot be used.
  static Expected<SyntheticScene> Create(std::string_view scenario, uint64_t seed = 1,
                                         const SyntheticBodySpec& body = {});
  static std::vector<std::string> ScenarioNames();

  const std::string& scenario() const;
  const SyntheticBodySpec& body() const;
  uint64_t seed() const;
  int frame_count() const;
  double frame_rate_hz() const;
  const PinholeCamera& sensor_camera() const;
  // The sensor's pose at `frame` (static or moving, per the scenario).
  // Precondition: 0 <= frame < frame_count().
  Eigen::Isometry3d world_from_sensor(int frame) const;
  // Ground truth skeleton in the world frame, every joint confidence 1 (joint placement in
  // body_model.h: head joint at the head's centre, neck at the base of the head, hands at
  // the palm centre, feet at the ankle; for a skinned body as skinned_body.h says).
  // Precondition: 0 <= frame < frame_count().
  Skeleton skeleton_in_world(int frame) const;
  Eigen::Vector3d world_up() const { return Eigen::Vector3d::UnitZ(); }

  // Renders frame `frame` from any undistorted camera. Throws CheckError on a frame out of
  // range, a camera with distortion, or options that fail Check().
  SyntheticView Render(int frame, const PinholeCamera& camera,
                       const Eigen::Isometry3d& world_from_camera,
                       const SyntheticRenderOptions& options = {}) const;
  // Render() from the sensor.
  SyntheticView RenderSensor(int frame, const SyntheticRenderOptions& options = {}) const;

  struct Data;

 private:
  explicit SyntheticScene(std::shared_ptr<const Data> data) : data_(std::move(data)) {}
  void CheckFrame(int frame) const;

  std::shared_ptr<const Data> data_;  // immutable, shared between copies
};

}  // namespace reenact::capture
