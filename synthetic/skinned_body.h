#pragma once
// The synthetic scene's realistic subject: a glTF skinned, textured mesh (gltf_skin.h, e.g.
// ../shared/data/models/CesiumMan.glb) posed on the CPU by linear blend skinning (double),
// from the model's own animation or retargeted onto any 16-joint Skeleton by bone directions,
// with the ground-truth skeleton, per-vertex body-part labels and drawing into a Rasterizer.
//
// Frames. Scene: the glTF file's frame (y up, +z the model's front, +x its left, file units).
// Body: as body_model.h (x forward, y to the subject's left, z up, metres), origin on the
// floor below the bind pose's root (waist) joint, floor z = 0 at the bind pose's lowest
// vertex. body_from_scene = scale * rotation + offset, fixed at creation; the rotation maps
// scene (z, x, y) to body (x, y, z), turned by a multiple of 90 degrees about the vertical
// when the bind pose's left hip does not lie on the model's +x side (a model facing -z or
// +-x is turned to face forward). World: z up, floor z = 0; a pose's world_from_body places
// the body (WorldFromBody: at yaw 0 the subject faces world -y, as the procedural body).
//
// Scale: the bind pose's standing height (top vertex minus lowest vertex) becomes
// SkinnedBodyOptions::height_m, or stays the model's own (CesiumMan: 1.51 m) when 0.
//
// The 16-joint skeleton (skeleton.h) from the skin's joints, by GltfJointsByName
// (joint_maps.h):
//  - neck, waist, shoulders, elbows, hips, knees, feet: the mapped joint node's origin
//    (CesiumMan: Skeleton_neck_joint_1, Skeleton_torso_joint_1, arm and leg joints; the
//    foot is the ankle joint leg_joint_*_3, as NiTE's);
//  - head and hands: a rig's head joint sits at the base of the skull and its hand joint at
//    the wrist, while ours are the head's centre and the palm's centre (body_model.h). So
//    they are the centroid of the bind-pose vertices whose dominant joint is the mapped
//    joint or one of its descendants, carried rigidly by the mapped joint node;
//  - torso: the mapped node where the rig names one, else (CesiumMan) mean(neck, waist).
// Every joint has confidence 1.
//
// Body-part labels (the 11 parts of skeleton.h): each skin joint gets a part: head and neck
// -> head, waist -> lower torso, torso -> upper torso, shoulder -> upper arm, elbow and hand
// -> forearm, hip -> thigh, knee and foot -> shin. A rig's joint moves the skin between it
// and its child, so the neck joint's skin is the neck above it, which the head's cylinder
// (neck -> head) covers: the procedural body's neck segment lies below its neck joint
// (body_model.h) and is upper torso, a rig's lies above (CesiumMan's neck joint sits 6 cm
// above its shoulders, its neck skin up to the skull's base). A joint that is none of
// these takes its nearest labelled ancestor's part, except spine joints between the waist
// and the neck, which are upper torso when their bind position lies above the torso joint
// along the waist-neck line, else lower torso. A vertex carries the part of its dominant
// (largest weight) joint, except that a vertex dominated by the waist or a spine joint below
// the neck is upper torso when its bind position lies above the torso joint along the
// waist-neck line, else lower torso (so the torso's two parts meet at the torso joint, as
// the cylinders of the skeleton do, even where one rig joint spans both). A drawn pixel
// carries the part of its surface point by the same rule, with the point's skin weights and
// bind position interpolated from its triangle's three vertices (barycentric; the dominant
// joint's ties to the lower joint index): so part borders run where the dominant joint
// changes on the surface, not along the low-polygon mesh's edges (CesiumMan's triangles span
// up to several centimetres), and the torso's two parts meet exactly at the torso joint's
// height.
//
// Retargeting (RetargetPose) by bone directions, starting from the bind pose, parents first:
//  1. pelvis: the waist joint node turns so that the skin's lower spine (waist -> torso;
//     with a derived torso that is waist -> neck before step 2) is parallel to the target's
//     (waist -> neck where the target has no torso) and, about it, the hip line (right hip
//     -> left hip) lies in the plane of the target's lower spine and hip line;
//  2. chest: with a torso joint in the rig, that node turns so that torso -> neck is
//     parallel to the target's, the shoulder line fixing the twist as the hip line did.
//     Without one (CesiumMan), the first spine node above the waist turns so that
//     waist -> neck is parallel to the target's waist -> neck (a rotation about that node
//     moving the neck onto the ray from the waist), then about its axis so that the
//     shoulder line lies in the target's plane;
//  3. neck -> head, shoulder -> elbow, elbow -> hand, hip -> knee, knee -> foot: the
//     proximal joint's node turns by the minimal rotation that makes the bone parallel to
//     the target's; other joints (wrists, toes, fingers) keep their bind rotation relative
//     to their parent;
//  4. placement: the skin's waist goes above the target's waist (x, y); then the whole body
//     moves vertically so that its lowest vertex touches the floor (z = 0): the skin keeps
//     its own bone lengths, so the target's waist height is not kept (a jump is not
//     reproduced).
// A bone whose target joints are missing or coincide keeps its bind rotation.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "common/error/expected.h"
#include "common/render/rasterizer.h"
#include "common/skeleton/skeleton.h"
#include "synthetic/gltf_skin.h"
#include "synthetic/synthetic_scene.h"

namespace reenact::capture {

struct SkinnedBodyOptions {
  // Standing height of the bind pose in metres, > 0; 0 keeps the model's own. Default 0.
  double height_m = 0;

  // Throws CheckError when a field is out of range.
  void Check() const;
};

// world_from_body of a subject standing with its body origin at (x, y, 0) and turned by yaw
// (radians, counter-clockwise seen from above) from facing world -y.
Eigen::Isometry3d WorldFromBody(const Eigen::Vector2d& root_xy = Eigen::Vector2d::Zero(),
                                double yaw = 0);

// A pose of the skin: every node's local transform (scene units) and the body's placement.
struct SkinPose {
  std::vector<NodeTransform> local;  // one per glTF node
  Eigen::Isometry3d world_from_body = WorldFromBody();
};

// A skinned pose, everything in the world frame (metres).
struct PosedSkin {
  std::vector<Eigen::Vector3d> positions;        // one per vertex
  std::vector<Eigen::Vector3d> normals;          // one per vertex, unit
  std::vector<Eigen::Affine3d> world_from_node;  // one per glTF node (includes the scale)
  Skeleton skeleton;                             // the 16 joints (see the header comment)
};

class SkinnedBody {
 public:
  // Errors: "unsupported" when the skin's joint names do not give every joint of our
  // skeleton but the torso (message: which are missing), or its hierarchy does not chain
  // them (e.g. an elbow that is not below its shoulder); "corrupt" for a mesh of zero height.
  static Expected<SkinnedBody> Create(GltfSkinModel model, const SkinnedBodyOptions& options = {});
  // LoadGltfSkin, then Create.
  static Expected<SkinnedBody> Load(const std::string& path,
                                    const SkinnedBodyOptions& options = {});

  const GltfSkinModel& model() const;
  double height_m() const;         // standing height of the bind pose, metres
  double metres_per_unit() const;  // the uniform scale from scene units to metres
  const Eigen::Affine3d& body_from_scene() const;

  // The bind pose placed by world_from_body.
  SkinPose BindPose(const Eigen::Isometry3d& world_from_body = WorldFromBody()) const;
  // The model's animation at t_s seconds (looping, SampleAnimation), placed by
  // world_from_body and then moved vertically so that its lowest vertex touches the floor
  // (CesiumMan's walk, on the bind pose's floor, would sink up to 2.3 cm into it and float up
  // to 3.5 cm above it). Precondition (CHECK): a valid animation index.
  SkinPose AnimationPose(int animation, double t_s,
                         const Eigen::Isometry3d& world_from_body = WorldFromBody()) const;
  // The bind pose retargeted onto target (world frame) by bone directions (see above).
  // Error "invalid_argument" when the target lacks the waist or a hip.
  Expected<SkinPose> RetargetPose(const Skeleton& target_in_world) const;

  // Linear blend skinning of a pose. Precondition (CHECK): pose.local has one per node.
  PosedSkin Skin(const SkinPose& pose) const;
  // Only the node transforms and the skeleton of a pose (no vertices).
  PosedSkin SkinJointsOnly(const SkinPose& pose) const;

  BodyPart JointPart(int joint) const;  // the part of skin joint `joint` (joint order)
  const std::vector<BodyPart>& vertex_parts() const;
  // For our joint j: the glTF node it is attached to, and its offset in that node's frame
  // (zero but for the head and the hands); node -1 for a derived torso.
  int JointNode(Joint j) const;
  Eigen::Vector3d JointOffset(Joint j) const;

  // Draws the posed skin like the procedural body (synthetic_scene.cc): colour = base colour
  // (bilinear texture sample times the factor) times LambertShade of the world normal, mask
  // 255, part label of the surface point (above), depth through the rasteriser. The
  // rasteriser needs attribute_count 8 (u, v, normal, bind position); back faces are culled
  // as its options say.
  // ambient: LambertShade's ambient share (room.h).
  void Draw(const PosedSkin& posed, const Eigen::Isometry3d& camera_from_world, Rasterizer* r,
            SyntheticView* view, double ambient = kSceneAmbient) const;

  struct Data;

 private:
  explicit SkinnedBody(std::shared_ptr<const Data> data) : data_(std::move(data)) {}
  // Moves the pose vertically so that its lowest skinned vertex lies at z = 0.
  void PlaceOnFloor(SkinPose* pose) const;
  std::shared_ptr<const Data> data_;
};

}  // namespace reenact::capture
