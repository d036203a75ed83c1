#pragma once
// The reenactment of a clip (thesis Sec. 3.4): for an output frame k and a viewer camera,
// pose the cylinder model from stored skeleton S'_k in the viewer frame (S*_k = M* S'_k),
// choose the stored frame n_bar by Eq. 5 and map every cylinder onto that frame's cylinder
// (Eq. 6-16), producing the renderer's draw list.
// Option steady_motion (issue 9, default off): the posed skeleton S'_k is taken from the
// steady track (common/filter/steady_motion.h: flagged skeletons interpolated across, joints
// One Euro filtered over the frames' timestamps) instead of the stored one, and so is every
// unflagged stored frame's own skeleton S'_n wherever the clip uses it (selection, the mapping
// onto the frame, its part-label maps, the shape and light fits at load): the pose shown and
// the frames it is textured from then agree, so at the sensor's own view frame k still maps
// onto itself, and a tracker's jitter leaves the stored mapping as well as the pose. Flagged
// frames keep their skeletons and stay out of texturing.
// Texturing (issue 9, TexturingOptions; default the thesis): the stored frames may be chosen
// per body part (common/texture/part_selection.h) with a few ranked candidates per part,
// drawn by the renderer's occlusion-aware or blending modes (common/render/texturing.h),
// held across output frames by hysteresis (the caller keeps a PartSelectionHistory per
// viewer stream), and relit from their recorded pose to the shown one.

#include <Eigen/Geometry>
#include <array>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include "common/filter/steady_motion.h"
#include "common/model/cylinder_model.h"
#include "common/model/surface_fit.h"
#include "common/render/texturing.h"
#include "common/texture/part_selection.h"
#include "common/texture/subject_light.h"
#include "common/texture/texture_index.h"
#include "common/texture/visibility_maps.h"
#include "proto/clip/frame_codec.h"
#include "proto/clip/manifest.h"
#include "viewer-client/render/renderer.h"

namespace reenact::viewer {

struct ReenactedFrame {
  FrameDraw draw;
  // The body part of each draw.cylinders entry, in the same order.
  std::vector<BodyPart> cylinder_parts;
  int clip_frame = -1;  // k
  // n_bar, -1 if no stored frame could be chosen; with per-part selection the upper torso's
  // first candidate.
  int texture_frame = -1;
};

enum class TextureSelection {
  kWholeBody,  // thesis Eq. 5: one stored frame for the whole body
  kPerPart,    // common/texture/part_selection.h: ranked candidates per body part
};

// The body model's shape (issue 9, a closer shape), in the drawn cylinders and in the stored
// frames' part-label maps alike.
enum class BodyShape {
  kCylinders,  // the thesis's cylinders between the joints
  kExtended,   // the head, forearms and shins extended past their end joints by the clip's
               // fitted extensions (Reenactment::part_extensions(); extension_fit.h)
  kProfiled,   // extended, and each part's radius varying along its axis through 5 rings,
               // the torso elliptic (Reenactment::part_shapes(); cross_section_fit.h)
  kSurface,    // profiled, and each part's radius varying around its axis as well, fitted
               // from the stored frames' depth, with rounded ends at the limbs' joints
               // (Reenactment::part_surfaces(); surface_fit.h). Textured by Eq. 6-16 like the
               // others: the mapping carries each point of the drawn surface onto the stored
               // frame's part turned about its axis by the difference in facing, so the
               // fitted surface's points project where that frame saw the part's near side
};


struct TexturingOptions {
  TextureSelection selection = TextureSelection::kWholeBody;
  TexturingMode mode = TexturingMode::kFirst;  // how the renderer uses the candidates
  // Candidates per part, [1, kMaxTextureCandidates]; whole-body selection takes exactly 1.
  int candidates = 1;
  // Fallback candidates per part (part_selection.h PartSelectionOptions::fallback_k), drawn
  // after the ranked ones: frames chosen to see what of the part the ranked candidates do not
  // (part_coverage.h), used where no ranked one is visible and the first usable one's texel
  // shows another part (texturing.h). Per-part selection with a visibility mode only;
  // candidates + fallback_candidates at most kMaxTextureCandidates.
  int fallback_candidates = 0;
  // Per-part selection: cost discount of the previous output frame's choice, [0, 1).
  double hysteresis = 0;
  double missing_joint_cost_m = 1.0;  // >= 0, as in Eq. 5
  BodyShape shape = BodyShape::kCylinders;
  // Relighting (issue 9): each stored colour re-shaded from the pose it was recorded in to
  // the pose shown, under the clip's fitted subject light (Reenactment::subject_light();
  // common/texture/subject_light.h). No effect where no light was found.
  bool relight = false;

  // Throws CheckError when a field is out of range or the combination is not supported.
  void Check() const;
};

struct ReenactmentOptions {
  bool steady_motion = false;  // pose and stored frames from the steady track (see above)
  SteadyMotionOptions steady;  // how the steady track is made
  TexturingOptions texturing;  // used by Build

  void Check() const {
    steady.Check();
    texturing.Check();
  }
};

class Reenactment {
 public:
  // frames: the clip's decoded frames, in order (manifest.frame_count of them).
  Reenactment(proto::ClipManifest manifest, std::vector<proto::ClipFrame> frames,
              const ReenactmentOptions& options = {});

  int frame_count() const { return static_cast<int>(frames_.size()); }
  const proto::ClipManifest& manifest() const { return manifest_; }
  // Frame n as stored, its skeleton the steady one under steady_motion (unless flagged).
  const proto::ClipFrame& frame(int n) const { return frames_.at(n); }

  // Mean waist position over the clip (world frame): the centre the orbit camera turns about.
  Eigen::Vector3d SubjectCentre() const;

  // The stored crop of frame n as the renderer uploads it, with its visibility maps
  // (common/texture/visibility_maps.h: part labels of the posed cylinder model, depth in
  // metres) and, where the clip's subject light was found, its depth normals for relighting
  // (common/texture/subject_light.h DepthNormalMap), computed here on each call (the caller
  // uploads each frame once). The part labels come from the shape options().texturing draws,
  // or the one named.
  StoredTexture Texture(int n) const;
  StoredTexture Texture(int n, BodyShape shape) const;

  // Extension of each part past its end joint (cylinder_model.h), fitted at load from the
  // representative frame and up to 8 other usable frames (common/model/extension_fit.h); the
  // shape BodyShape::kExtended and kProfiled draw.
  const PartExtensions& part_extensions() const { return part_extensions_; }

  // Cross-sections of each part along its extended axis (radius rings, elliptic torso),
  // fitted at load from the representative frame and up to 24 other usable frames spread
  // over the clip (common/model/cross_section_fit.h); the shape BodyShape::kProfiled draws.
  const PartShapes& part_shapes() const { return part_shapes_; }

  // Each part's surface (surface_fit.h) on top of part_shapes(), fitted at load from the depth
  // of the same frames as the cross-sections; the shape BodyShape::kSurface draws. The fit's
  // held-out errors and chosen resolutions are surface_fit().
  const PartShapes& part_surfaces() const { return surface_fit_.shape; }
  const SurfaceFitResult& surface_fit() const { return surface_fit_; }

  // The light on the subject (world frame), fitted at load from the colours, depth normals and
  // profiled part labels of the representative frame and up to 24 other usable frames spread
  // over the clip (common/texture/subject_light.h); TexturingOptions::relight uses it.
  const SubjectLightFit& subject_light() const { return subject_light_; }

  // Draw list for output frame k seen by a viewer camera, with options().texturing.
  // texture_for_frame maps a stored frame index to the renderer's texture index (the caller
  // uploads Texture(n) on demand). history (per-part selection with hysteresis; may be null)
  // carries the choice from one output frame to the next of the same viewer stream.
  ReenactedFrame Build(int k, const PinholeCamera& viewer_camera,
                       const Eigen::Isometry3d& viewer_from_world,
                       const std::function<int(int)>& texture_for_frame,
                       PartSelectionHistory* history = nullptr) const;

  // The same with the skeleton to pose (world frame, e.g. the steady one) and the texturing
  // given explicitly.
  ReenactedFrame BuildPosed(int k, const Skeleton& skeleton_in_world,
                            const PinholeCamera& viewer_camera,
                            const Eigen::Isometry3d& viewer_from_world,
                            const std::function<int(int)>& texture_for_frame,
                            const TexturingOptions& texturing,
                            PartSelectionHistory* history = nullptr) const;

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
  TextureIndex texture_index_;  // Eq. 5 over usable S_n, exact as the scan
  // Per-part selection over usable frames, each part only where it lies inside the crop.
  PartTextureIndex part_index_;
  // The same with every frame's coverage of each part (part_coverage.h) in the labels of a
  // body shape, indexed by BodyShape (fallback candidates): built at load for the shape of
  // options().texturing when it has fallback candidates, else on first use; 2.0-3.2 ms per
  // usable stored frame (0.4-0.7 s for the 180-225 frames of the synthetic clips).
  struct CoverageIndex {
    std::once_flag built;
    PartTextureIndex index;
  };
  std::unique_ptr<std::array<CoverageIndex, 4>> coverage_index_ =
      std::make_unique<std::array<CoverageIndex, 4>>();
  std::vector<uint16_t> part_allowed_;
  const PartTextureIndex& CoverageIndexOf(BodyShape shape) const;
  std::vector<Skeleton> steady_in_world_;  // the steady track, world frame
  PartExtensions part_extensions_{};
  PartShapes part_shapes_{};
  SurfaceFitResult surface_fit_{};
  SubjectLightFit subject_light_{};

  // Construction, in order: the flags of the frames whose skeleton the capture flagged; the
  // steady track (replacing the unflagged frames' skeletons with steady_motion); sensor-frame
  // skeletons, usable frames and the selection indices over them; part extensions and
  // cross-sections; the subject light.
  std::unique_ptr<bool[]> FlaggedFrames() const;
  void SteadyMotion(const bool* flagged);
  void IndexFrames(const bool* flagged);
  void FitShapes();
  void FitLight();

  // Frame n's crop camera, and its part-label map (drawn with `shape`) and depth in metres.
  PinholeCamera CropCamera(int n) const;
  VisibilityMaps VisibilityMapsOf(int n, BodyShape shape) const;

  // The extensions and cross-sections a shape draws with.
  std::pair<PartExtensions, PartShapes> ShapeOf(BodyShape shape) const;
};

}  // namespace reenact::viewer
