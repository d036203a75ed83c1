#pragma once
// The reenactment of a clip (thesis Sec. 3.4): for an output frame k and a viewer camera,
// pose the cylinder model from stored skeleton S'_k in the viewer frame (S*_k = M* S'_k),
// choose the stored frame n_bar by Eq. 5 and map every cylinder onto that frame's cylinder
// (Eq. 6-16), producing the renderer's draw list.
// Option steady_motion (issue 9, default off): the posed skeleton S'_k is taken from the
// steady track (common/filter/steady_motion.h: flagged skeletons interpolated across, joints
// One Euro filtered over the frames' timestamps) instead of the stored one; texture selection
// still ranks the stored, unflagged skeletons.

#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "common/filter/steady_motion.h"
#include "common/model/cylinder_model.h"
#include "common/texture/texture_index.h"
#include "proto/clip/frame_codec.h"
#include "proto/clip/manifest.h"
#include "viewer-client/render/renderer.h"

namespace reenact::viewer {

struct ReenactedFrame {
  FrameDraw draw;
  // The body part of each draw.cylinders entry, in the same order.
  std::vector<BodyPart> cylinder_parts;
  int clip_frame = -1;     // k
  int texture_frame = -1;  // n_bar, -1 if no stored frame could be chosen
};

struct ReenactmentOptions {
  bool steady_motion = false;  // pose from the steady track (see above)
  SteadyMotionOptions steady;  // how the steady track is made

  void Check() const { steady.Check(); }
};

class Reenactment {
 public:
  // frames: the clip's decoded frames, in order (manifest.frame_count of them).
  Reenactment(proto::ClipManifest manifest, std::vector<proto::ClipFrame> frames,
              const ReenactmentOptions& options = {});

  int frame_count() const { return static_cast<int>(frames_.size()); }
  const proto::ClipManifest& manifest() const { return manifest_; }
  const proto::ClipFrame& frame(int n) const { return frames_.at(n); }

  // Mean waist position over the clip (world frame): the centre the orbit camera turns about.
  Eigen::Vector3d SubjectCentre() const;

  // The stored crop of frame n as the renderer uploads it.
  StoredTexture Texture(int n) const;

  // Draw list for output frame k seen by a viewer camera. texture_for_frame maps a stored
  // frame index to the renderer's texture index (the caller uploads Texture(n) on demand).
  ReenactedFrame Build(int k, const PinholeCamera& viewer_camera,
                       const Eigen::Isometry3d& viewer_from_world,
                       const std::function<int(int)>& texture_for_frame) const;

  // The same with the skeleton to pose given explicitly (world frame), e.g. the steady one.
  ReenactedFrame BuildPosed(int k, const Skeleton& skeleton_in_world,
                            const PinholeCamera& viewer_camera,
                            const Eigen::Isometry3d& viewer_from_world,
                            const std::function<int(int)>& texture_for_frame) const;

  // Frame k's skeleton in the world frame from the steady track (always computed, with
  // options.steady, whether or not steady_motion is on).
  const Skeleton& SteadySkeletonInWorld(int k) const { return steady_in_world_.at(k); }
  const ReenactmentOptions& options() const { return options_; }

 private:
  ReenactmentOptions options_;
  proto::ClipManifest manifest_;
  std::vector<proto::ClipFrame> frames_;
  std::vector<Skeleton> skeletons_in_sensor_;  // S_n = M_n S'_n
  // Frames with a visible subject whose skeleton the capture did not flag.
  std::unique_ptr<bool[]> usable_;
  TextureIndex texture_index_;                 // Eq. 5 over usable S_n, exact as the scan
  std::vector<Skeleton> steady_in_world_;      // the steady track, world frame
};

}  // namespace reenact::viewer
