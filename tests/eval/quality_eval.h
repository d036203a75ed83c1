#pragma once
// `reenact-eval quality`: capture a synthetic scenario through the real recording pipeline,
// reenact every frame_step-th frame with each method (quality_methods.h) from orbit
// viewpoints turned by each angle about the subject's vertical axis, render the ground truth
// from the very same camera, and compare:
//   - PSNR, SSIM, silhouette IoU, colour error of the GL rendering (image_metrics.h; PSNR
//     and SSIM over the bounding box of the union of both silhouettes, kCropRule);
//   - wrong-part rate and seen-part rate (part_provenance.h), with provenance from the CPU
//   reference renderer
//     (common/render/reference_renderer.h) drawing the same draw list; reference_iou, the
//     silhouette IoU of the two renderings, shows they drew the same thing;
//   - flicker (temporal_flicker.h) between consecutive evaluated frames k and k + frame_step
//     at the same view, mean over those pairs;
//   - milliseconds per rendered frame: draw-list build (selection + mapping) + GL draw +
//     read-back, median over the frames.
// Output frame k is compared with the scene's frame k; the source frame's part labels are
// the scene's labels rendered from the sensor at that stored frame (cached).

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "common/error/expected.h"
#include "common/render/reference_renderer.h"
#include "synthetic/synthetic_scene.h"
#include "tests/eval/image_metrics.h"
#include "tests/eval/part_provenance.h"
#include "tests/eval/quality_methods.h"
#include "tests/eval/temporal_flicker.h"
#include "viewer-client/play/reenactment.h"
#include "viewer-client/render/renderer.h"

namespace reenact::eval {

// The crop rule, as printed with every table.
inline constexpr const char* kCropRule =
    "PSNR and SSIM over the bounding box of the union of the true and rendered silhouettes, "
    "each image's subject on black (a missing or extra limb counts, the empty background "
    "around the box does not)";

// One picture for the docs: output frame `frame` seen from orbit angle `view_deg`.
struct ImagePair {
  int frame = 0;
  double view_deg = 0;
};

struct QualityOptions {
  std::string scenario = "turn-and-kick";  // a SyntheticScene scenario name
  // The subject's body: empty for the procedural body (no data file needed), else the path
  // of a skinned glTF model (e.g. ../shared/data/models/CesiumMan.glb; synthetic_scene.h).
  std::string body;
  std::vector<std::string> methods = {"thesis"};
  // Tracker-like jitter on the recorded skeletons, metres (>= 0, finite; 0 = the scene's exact
  // skeletons): every joint of every frame moved by independent Gaussian noise of this
  // deviation per axis in the sensor frame, seeded by the frame index (repeatable). Skeletons
  // it pushes past the bone-length check are flagged by the recorder as for real ones. The
  // ground truth stays exact.
  double skeleton_noise_m = 0;
  // The recorded skeletons from our depth tracker (capture-client/tracker/) reading each
  // rendered depth frame, as a sensor without NiTE records them, instead of the scene's exact
  // ones; the ground truth stays exact. Not with skeleton_noise_m. The recorder stores only
  // frames with a skeleton, so a frame the tracker loses is not in the clip: output frame k is
  // the clip's k-th and is compared with the scene at that frame's time
  // (QualityHarness::SceneFrame), as a viewer plays such a clip.
  bool tracked_skeletons = false;
  // The subject lit flat (SyntheticBodySpec::ambient 1, no directional light) in the recording
  // and in the ground truth alike: no shading for texturing to carry from one pose to
  // another, so what stays is geometry and texture choice. Default: the scene's light.
  bool flat_lighting = false;
  std::vector<double> views_deg = {0, 30, 60, 90, 135, 180};  // finite
  int frame_step = 10;  // >= 1: frames 0, step, 2 step, ... are compared
  int width = 640;      // output size, >= 16 each
  int height = 480;
  // Side-by-side pictures (side_by_side.h) as PNG files in image_dir, one per method and
  // pair; none when image_dir is empty. No pairs given: at every view, the compared frame
  // nearest the middle of the clip.
  std::string image_dir;
  std::vector<ImagePair> image_pairs;  // frames >= 0 (and < the clip's frame count)

  // Throws CheckError when a field is out of range.
  void Check() const;
};

struct QualityRow {
  std::string method;
  std::string scenario;
  double view_deg = 0;
  int n = 0;           // frames compared
  double psnr_db = 0;  // mean over frames with finite PSNR
  double ssim = 0;     // means over the frames
  double iou = 0;
  double colour_mae = 0;            // 0..255
  double wrong_part_rate = 0;       // 0..1, against the drawn cylinder's part
  double wrong_seen_part_rate = 0;  // 0..1, against the part the truth shows there
  double wrong_texture_rate = 0;    // 0..1, of that where the truth shows the drawn part
  double doubled_limb_rate = 0;     // 0..1, another part that the truth shows nowhere near
  double untextured_rate = 0;       // 0..1, share of subject pixels in flat colour
  double reference_iou = 0;         // GL vs reference silhouette (provenance check)
  double ms_per_frame = 0;          // median
  // Means over the n - 1 pairs of consecutive evaluated frames (temporal_flicker.h), 0..255.
  double reenacted_change = 0;
  double truth_change = 0;
  double flicker = 0;  // reenacted_change - truth_change
  double error_change = 0;
};

struct QualityImage {
  std::string method;
  ImagePair pair;
  std::string path;              // the PNG written
  SubjectComparison comparison;  // of this frame
  double wrong_part_rate = 0;
  double wrong_seen_part_rate = 0;
  double wrong_texture_rate = 0;
  double doubled_limb_rate = 0;
};

struct QualityRun {
  std::vector<QualityRow> rows;  // per method, then view
  std::vector<QualityImage> images;
  int clip_frames = 0;      // frames captured
  int scene_frames = 0;     // the scenario's frames: more than clip_frames where one was lost
  std::string gl_renderer;  // GL_RENDERER of the headless context
  // The clip's subject light as fitted at load (viewer::Reenactment::subject_light()) and the
  // scene's true one in the same form (common/texture/subject_light.h: world frame, strength
  // relative to the ambient light; zero when the subject is lit flat).
  SubjectLightFit subject_light;
  Eigen::Vector3d true_subject_light = Eigen::Vector3d::Zero();
  // The clip's part surfaces as fitted at load (viewer::Reenactment::surface_fit()).
  SurfaceFitResult surface_fit;
};

// Everything about one compared frame.
struct FrameEvaluation {
  viewer::ReenactedFrame frame;    // the method's draw list
  viewer::RenderedFrame rendered;  // GL
  ReferenceRender reference;       // CPU reference of the same draw list
  capture::SyntheticView truth;    // ground truth from the viewer camera, no room
  SubjectComparison comparison;    // rendered vs truth
  PartProvenance provenance;
  double reference_iou = 0;
  double ms = 0;  // build + GL draw + read-back
};

// A captured scenario with a headless renderer: evaluates single frames. Move-only.
class QualityHarness {
 public:
  // Captures options.scenario (record + read back, in a temporary directory) and opens the
  // headless renderer. Errors: unknown scenario ("not_found", listing the known ones),
  // recording failures, "tracking" (--skeletons track: the tracker found no one),
  // "internal" (a clip frame's timestamp is not one of the scene's frames), "gl_unavailable".
  static Expected<QualityHarness> Create(const QualityOptions& options);

  QualityHarness(QualityHarness&&) noexcept;
  QualityHarness& operator=(QualityHarness&&) noexcept;
  ~QualityHarness();

  const viewer::Reenactment& clip() const;
  const capture::SyntheticScene& scene() const;
  const PinholeCamera& camera() const;  // the viewer camera (options' size)
  const std::string& gl_renderer() const;
  // The scene frame that clip frame n (0 <= n < clip().frame_count(), CHECK) was recorded
  // from, found from its timestamp: n itself unless the tracker lost an earlier frame.
  int SceneFrame(int n) const;

  // The orbit camera's viewer_from_world at that angle; error "degenerate" if it cannot be
  // placed.
  Expected<Eigen::Isometry3d> ViewerFromWorld(double view_deg) const;

  // Output frame k (0 <= k < clip().frame_count(), CHECK) of the method from the view.
  // history: as QualityMethod::build's (may be null).
  Expected<FrameEvaluation> Evaluate(const QualityMethod& method, double view_deg, int k,
                                     PartSelectionHistory* history = nullptr);

  struct State;

 private:
  explicit QualityHarness(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

// The whole run. Errors: unknown method ("usage", listing the known ones), the errors of
// QualityHarness::Create, an image pair out of the clip, an image that cannot be written.
Expected<QualityRun> RunQuality(const QualityOptions& options);

}  // namespace reenact::eval
