#include "synthetic/synthetic_scene.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "common/error/check.h"
#include "common/render/rasterizer.h"
#include "synthetic/body_mesh.h"
#include "synthetic/body_model.h"
#include "synthetic/body_pose_from_skeleton.h"
#include "synthetic/body_texture.h"
#include "synthetic/depth_noise.h"
#include "synthetic/procedural.h"
#include "synthetic/room.h"
#include "synthetic/scenario.h"
#include "synthetic/skinned_body.h"

namespace reenact::capture {

struct SyntheticScene::Data {
  Scenario scenario;
  uint64_t seed = 1;
  PinholeCamera camera;
  std::shared_ptr<const RoomModel> room;
  SyntheticBodySpec body_spec;
  // The procedural body (when body_spec is not skinned):
  std::array<SegmentMesh, kSegmentCount> body;
  std::vector<PosedBody> posed;  // per frame
  // The skinned body:
  std::shared_ptr<const SkinnedBody> skinned;
  std::vector<SkinPose> skin_poses;      // per frame
  std::vector<Skeleton> skin_skeletons;  // per frame
};

namespace {

uint8_t ToByte(float v) { return static_cast<uint8_t>(std::clamp(v + 0.5f, 0.0f, 255.0f)); }

void DrawRoom(const RoomModel& room, const Eigen::Isometry3d& camera_from_world, Rasterizer* r,
              SyntheticView* view) {
  auto shader = [&](const RasterFragment& f) {
    const Eigen::Vector3f c =
        SampleFace(room.faces[f.primitive_id], f.attributes[0], f.attributes[1]);
    for (int k = 0; k < 3; ++k) view->color.at(f.x, f.y, k) = ToByte(c[k]);
    view->mask.at(f.x, f.y) = 0;
    view->part_labels.at(f.x, f.y) = kBackgroundLabel;
    return true;
  };
  for (size_t i = 0; i < room.faces.size(); ++i) {
    const RoomFace& face = room.faces[i];
    std::array<RasterVertex, 4> v;
    const double uv[4][2] = {{0, 0}, {face.width, 0}, {face.width, face.height}, {0, face.height}};
    for (int k = 0; k < 4; ++k) {
      v[k].position =
          camera_from_world * (face.origin + uv[k][0] * face.u_axis + uv[k][1] * face.v_axis);
      v[k].attributes[0] = static_cast<float>(uv[k][0]);
      v[k].attributes[1] = static_cast<float>(uv[k][1]);
    }
    r->DrawTriangle(v[0], v[1], v[2], static_cast<int>(i), shader);
    r->DrawTriangle(v[0], v[2], v[3], static_cast<int>(i), shader);
  }
}

void DrawBody(const std::array<SegmentMesh, kSegmentCount>& meshes, const PosedBody& body,
              const Eigen::Isometry3d& camera_from_world, double ambient, Rasterizer* r,
              SyntheticView* view) {
  auto shader = [&](const RasterFragment& f) {
    const Segment segment = static_cast<Segment>(f.primitive_id);
    const Eigen::Vector3d local(f.attributes[0], f.attributes[1], f.attributes[2]);
    const Eigen::Vector3d normal =
        Eigen::Vector3d(f.attributes[3], f.attributes[4], f.attributes[5]).normalized();
    const Color c = BodyAlbedo(segment, local) * (LambertShade(normal, ambient) * 255.0);
    for (int k = 0; k < 3; ++k) view->color.at(f.x, f.y, k) = ToByte(static_cast<float>(c[k]));
    view->mask.at(f.x, f.y) = 255;
    view->part_labels.at(f.x, f.y) = static_cast<uint8_t>(PartLabel(SegmentPart(segment)));
    return true;
  };
  std::vector<RasterVertex> vertices;
  for (int s = 0; s < kSegmentCount; ++s) {
    const SegmentMesh& mesh = meshes[s];
    const Eigen::Isometry3d& world_from_segment = body.world_from_segment[s];
    const Eigen::Isometry3d camera_from_segment = camera_from_world * world_from_segment;
    vertices.resize(mesh.positions.size());
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      const Eigen::Vector3d& p = mesh.positions[i];
      const Eigen::Vector3d n = world_from_segment.linear() * mesh.normals[i];
      vertices[i].position = camera_from_segment * p;
      for (int k = 0; k < 3; ++k) {
        vertices[i].attributes[k] = static_cast<float>(p[k]);
        vertices[i].attributes[3 + k] = static_cast<float>(n[k]);
      }
    }
    for (const Eigen::Vector3i& t : mesh.triangles)
      r->DrawTriangle(vertices[t[0]], vertices[t[1]], vertices[t[2]], s, shader);
  }
}

}  // namespace

void SyntheticRenderOptions::Check() const {
  REENACT_CHECK(std::isfinite(min_depth_m) && std::isfinite(max_depth_m) && min_depth_m >= 0 &&
                    min_depth_m < max_depth_m && max_depth_m <= 65.5,
                "depth range must satisfy 0 <= min_depth_m < max_depth_m <= 65.5");
  noise.Check();
}

Expected<SyntheticScene> SyntheticScene::Create(std::string_view scenario, uint64_t seed,
                                                const SyntheticBodySpec& body) {
  Expected<Scenario> made = MakeScenario(scenario, seed);
  if (!made.ok()) return made.error();
  if (made->poses.empty() && made->target_skeletons.empty() && !body.skinned())
    return MakeError("unsupported", "scenario '" + made->name +
                                        "' needs a skinned body (it plays the model's own "
                                        "animation); the procedural body plays procedural "
                                        "scenarios such as turn-and-kick and bvh: motion. Give "
                                        "a glTF skinned mesh, e.g. "
                                        "../shared/data/models/CesiumMan.glb");
  REENACT_CHECK(static_cast<int>(made->world_from_sensor.size()) == made->frame_count(),
                "scenario '" + made->name + "' needs one world_from_sensor per frame");
  auto data = std::make_shared<Data>();
  data->scenario = std::move(made).value();
  data->seed = seed;
  data->camera = PinholeCamera::KinectLike();
  data->room = SharedRoom();
  if (!(std::isfinite(body.ambient) && body.ambient >= 0 && body.ambient <= 1))
    return MakeError("invalid_argument", "the subject's ambient light share must be in [0, 1]");
  data->body_spec = body;
  const Scenario& sc = data->scenario;
  if (!body.skinned()) {
    data->body = BuildBodyMeshes();
    for (const BodyPose& pose : sc.poses) data->posed.push_back(PoseBody(pose));
    for (const Skeleton& target : sc.target_skeletons)
      data->posed.push_back(PoseBody(BodyPoseFromSkeleton(target).pose));
    return SyntheticScene(std::move(data));
  }
  if (!(std::isfinite(body.height_m) && body.height_m >= 0 && body.height_m < 10))
    return MakeError("invalid_argument", "body height must be 0 (the model's own) or in (0, 10) m");
  SkinnedBodyOptions options;
  options.height_m = body.height_m;
  Expected<SkinnedBody> skinned = SkinnedBody::Load(body.gltf_path, options);
  if (!skinned.ok()) return skinned.error();
  data->skinned = std::make_shared<const SkinnedBody>(std::move(skinned).value());
  const SkinnedBody& b = *data->skinned;
  if (sc.model_animation && sc.poses.empty() && sc.target_skeletons.empty() &&
      b.model().animations.empty())
    return MakeError("unsupported", "scenario '" + sc.name +
                                        "' plays the model's own animation but " + body.gltf_path +
                                        " has none");
  for (int f = 0; f < sc.frame_count(); ++f) {
    Expected<SkinPose> pose = SkinPose{};
    if (!sc.poses.empty()) {
      pose = b.RetargetPose(PoseBody(sc.poses[f]).skeleton);
    } else if (!sc.target_skeletons.empty()) {
      pose = b.RetargetPose(sc.target_skeletons[f]);
    } else {
      pose = b.AnimationPose(0, f / sc.frame_rate_hz);
    }
    if (!pose.ok())
      return MakeError(pose.error().code, "scenario '" + sc.name + "' frame " + std::to_string(f) +
                                              ": " + pose.error().message);
    data->skin_skeletons.push_back(b.SkinJointsOnly(*pose).skeleton);
    data->skin_poses.push_back(std::move(pose).value());
  }
  return SyntheticScene(std::move(data));
}

std::vector<std::string> SyntheticScene::ScenarioNames() { return SyntheticScenarioNames(); }

const std::string& SyntheticScene::scenario() const { return data_->scenario.name; }
const SyntheticBodySpec& SyntheticScene::body() const { return data_->body_spec; }
uint64_t SyntheticScene::seed() const { return data_->seed; }
int SyntheticScene::frame_count() const { return data_->scenario.frame_count(); }
double SyntheticScene::frame_rate_hz() const { return data_->scenario.frame_rate_hz; }
const PinholeCamera& SyntheticScene::sensor_camera() const { return data_->camera; }

void SyntheticScene::CheckFrame(int frame) const {
  REENACT_CHECK(frame >= 0 && frame < frame_count(), "frame " + std::to_string(frame) +
                                                         " out of range [0, " +
                                                         std::to_string(frame_count()) + ")");
}

Eigen::Isometry3d SyntheticScene::world_from_sensor(int frame) const {
  CheckFrame(frame);
  return data_->scenario.world_from_sensor[frame];
}

Skeleton SyntheticScene::skeleton_in_world(int frame) const {
  CheckFrame(frame);
  return data_->skinned ? data_->skin_skeletons[frame] : data_->posed[frame].skeleton;
}

SyntheticView SyntheticScene::Render(int frame, const PinholeCamera& camera,
                                     const Eigen::Isometry3d& world_from_camera,
                                     const SyntheticRenderOptions& options) const {
  CheckFrame(frame);
  options.Check();
  RasterOptions raster;
  raster.near_z = 0.05;
  raster.attribute_count = 8;
  raster.cull = CullMode::kBack;
  Rasterizer r(camera, raster);
  SyntheticView view;
  view.color = ImageRgb8(camera.width, camera.height, 3, 0);
  view.depth = ImageDepthMm(camera.width, camera.height, 1, 0);
  view.mask = ImageGray8(camera.width, camera.height, 1, 0);
  view.part_labels = ImageLabel8(camera.width, camera.height, 1, kBackgroundLabel);
  const Eigen::Isometry3d camera_from_world = world_from_camera.inverse();
  if (options.draw_room) DrawRoom(*data_->room, camera_from_world, &r, &view);
  const double ambient = data_->body_spec.ambient;
  if (options.draw_subject && data_->skinned)
    data_->skinned->Draw(data_->skinned->Skin(data_->skin_poses[frame]), camera_from_world, &r,
                         &view, ambient);
  else if (options.draw_subject)
    DrawBody(data_->body, data_->posed[frame], camera_from_world, ambient, &r, &view);

  const Image<double>& z = r.depth();
  for (size_t i = 0; i < z.data.size(); ++i) {
    const double d = z.data[i];
    if (std::isfinite(d) && d >= options.min_depth_m && d <= options.max_depth_m)
      view.depth.data[i] = static_cast<uint16_t>(std::lround(d * 1000.0));
  }
  if (options.depth_noise)
    ApplyDepthNoise(&view.depth, camera,
                    Mix64(data_->seed) ^ Mix64(static_cast<uint64_t>(frame) + 1), options.noise);
  return view;
}

SyntheticView SyntheticScene::RenderSensor(int frame, const SyntheticRenderOptions& options) const {
  return Render(frame, sensor_camera(), world_from_sensor(frame), options);
}

}  // namespace reenact::capture
