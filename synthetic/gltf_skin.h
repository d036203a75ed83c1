#pragma once
// A glTF 2.0 skinned, textured mesh read into plain structs (double precision), the source
// of the synthetic scene's realistic body (skinned_body.h). Reads .glb and .gltf files (with
// embedded or external buffers and images) through Debian's libtinygltf, then validates
// everything it uses and turns it into the structs below.
//
// What is read:
//  - the node hierarchy (every node, its parent, children and rest transform; a node given
//    by a `matrix` is decomposed into translation, rotation and scale, which the glTF spec
//    requires to be possible);
//  - the first node (in node order) that has both a mesh and a skin, and that skin: its
//    joint nodes and inverse bind matrices (identity when absent, as the spec says);
//  - every primitive of that mesh (TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN, indexed or
//    not) merged into one vertex and triangle list: POSITION, NORMAL, the TEXCOORD set of
//    the base colour texture, JOINTS_0 / WEIGHTS_0 (and JOINTS_1 / WEIGHTS_1, of which the
//    four largest influences are kept);
//  - the material's base colour factor and base colour texture, decoded to 8-bit RGB (the
//    alpha channel is dropped: the body is drawn opaque);
//  - every animation's translation, rotation and scale channels (LINEAR or STEP).
//
// Repaired, with a line in GltfSkinModel::warnings: weights that do not sum to 1 (they are
// normalised), a missing NORMAL (area-weighted vertex normals), more than four influences
// per vertex, no base colour texture (the material's base colour factor is used, or white
// without a material), ignored parts (morph targets, other meshes, weight channels).
// Errors (Error.code): "not_found" (no such file), "io" (unreadable), "corrupt" (not glTF,
// truncated, an index or accessor out of range, a node hierarchy that is not a tree, a
// weight that is negative or all zero, an animation whose key times decrease, ...),
// "unsupported" (valid glTF that this reader does not handle: no skinned mesh, sparse
// accessors, CUBICSPLINE animation, points or lines, several materials on the skinned mesh,
// a glTF version other than 2.x). Every message names the file and the offending element.
//
// Frames and units: everything stays in glTF's own frame (the scene frame: y up, +z the
// asset's front, +x the asset's left, metres by the glTF convention); skinned_body.h maps it
// to the world. Linear blend skinning (glTF 2.0, "Skins"): a vertex v of the mesh is posed
//   v' = sum_i w_i * scene_from_node[joint_i] * inverse_bind[joint_i] * v,
// where scene_from_node is the product of the local transforms from the scene root down to
// the joint node. The mesh node's own transform does not apply to skinned vertices.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "common/error/expected.h"
#include "common/image/image.h"

namespace reenact::capture {

// A node's local transform parent_from_node = T * R * S (glTF order).
struct NodeTransform {
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // unit
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();

  Eigen::Affine3d Matrix() const;
};

struct GltfNode {
  std::string name;           // may be empty
  int parent = -1;            // node index, -1 for a root of the hierarchy
  std::vector<int> children;  // node indices
  NodeTransform rest;         // the local transform when no animation drives the node
};

struct SkinVertex {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // bind space (the mesh's frame)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   // bind space, unit length
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();       // texture coordinate, (0, 0) = top-left texel
  Eigen::Vector4i joints = Eigen::Vector4i::Zero();   // indices into GltfSkinModel::joint_nodes
  Eigen::Vector4d weights = Eigen::Vector4d::Zero();  // >= 0, summing to 1
};

enum class TextureWrap { kRepeat, kClampToEdge, kMirroredRepeat };

struct GltfTexture {
  ImageRgb8 image;  // 8-bit sRGB, 3 channels; empty when there is no texture
  TextureWrap wrap_u = TextureWrap::kRepeat;
  TextureWrap wrap_v = TextureWrap::kRepeat;
};

enum class AnimationPath { kTranslation, kRotation, kScale };
enum class AnimationInterpolation { kLinear, kStep };

struct GltfAnimationSampler {
  std::vector<double> times;  // seconds, non-decreasing, at least one
  // One value per time: (x, y, z, 0) for translation and scale, the unit quaternion
  // (x, y, z, w) for rotation.
  std::vector<Eigen::Vector4d> values;
  AnimationInterpolation interpolation = AnimationInterpolation::kLinear;
};

struct GltfAnimationChannel {
  int node = 0;  // the node it drives
  AnimationPath path = AnimationPath::kTranslation;
  int sampler = 0;  // index into GltfAnimation::samplers
};

struct GltfAnimation {
  std::string name;
  std::vector<GltfAnimationSampler> samplers;
  std::vector<GltfAnimationChannel> channels;
  double duration_s = 0;  // the largest key time of any channel (the loop period)
};

struct GltfSkinModel {
  std::string path;             // the file it was read from
  std::vector<GltfNode> nodes;  // index = glTF node index
  int mesh_node = -1;           // the node carrying the skinned mesh
  std::vector<SkinVertex> vertices;
  std::vector<Eigen::Vector3i> triangles;     // vertex indices, counter-clockwise = front
  std::vector<int> joint_nodes;               // skin joint i is node joint_nodes[i]
  std::vector<Eigen::Affine3d> inverse_bind;  // joint_from_bind_space, one per joint
  Eigen::Vector4d base_color_factor = Eigen::Vector4d::Ones();  // RGBA, multiplies texture
  GltfTexture base_color_texture;
  bool double_sided = false;  // the material's doubleSided
  std::vector<GltfAnimation> animations;
  std::vector<std::string> warnings;  // one line per repair or ignored part (see above)

  // The joint nodes' names, in joint order.
  std::vector<std::string> JointNames() const;
};

// Reads a .glb or .gltf file (the format is told by its first bytes, not its name).
Expected<GltfSkinModel> LoadGltfSkin(const std::string& path);

// The rest transform of every node (index = node).
std::vector<NodeTransform> RestTransforms(const GltfSkinModel& model);

// The local transform of every node at time t_s (seconds) of the animation: the rest
// transform where no channel drives a node. Between keys: LINEAR interpolates translation
// and scale linearly and rotation by slerp (shortest arc); STEP holds the earlier key.
// Before the first key the first value holds, after the last key the last value.
// loop: t_s is first wrapped into [0, duration_s) (no wrap when duration_s is 0).
// Precondition (CHECK): 0 <= animation < model.animations.size(), t_s finite.
std::vector<NodeTransform> SampleAnimation(const GltfSkinModel& model, int animation, double t_s,
                                           bool loop = true);

// scene_from_node of every node for the given local transforms (one per node).
// Precondition (CHECK): local.size() == model.nodes.size().
std::vector<Eigen::Affine3d> SceneFromNode(const GltfSkinModel& model,
                                           const std::vector<NodeTransform>& local);

// Local transforms of the bind pose: the rest transforms, except that every joint node gets
// the local transform that puts it at scene_from_mesh * inverse_bind^-1 in the scene frame,
// where scene_from_mesh is the mesh node's scene transform at rest. Skinning with them
// reproduces the mesh where its node places it: v' = scene_from_mesh * v (CesiumMan: its
// bind-space mesh is z-up, and the mesh node, below the root's Z_UP node, turns it y-up).
std::vector<NodeTransform> BindTransforms(const GltfSkinModel& model);

// The base colour (sRGB in [0, 1], RGB) at texture coordinate uv: bilinear over the four
// nearest texels (texel centres at half-integer coordinates, glTF's convention), with the
// texture's wrap modes, times the RGB of base_color_factor; the factor alone without a
// texture.
Eigen::Vector3d SampleBaseColor(const GltfSkinModel& model, const Eigen::Vector2d& uv);

}  // namespace reenact::capture
