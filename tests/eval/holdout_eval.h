#pragma once
// `reenact-eval holdout`: reenactment quality on held-out real views. From a recording of a
// person (any source with colour: synthetic:, oni:, tum:, rgbd:DIR with colour, clip:), every
// K-th frame is held out with its W neighbours on each side (holdout_frames.h); the clip is
// recorded from the rest through the real capture pipeline; each held-out frame is reenacted
// by each method (quality_methods.h) from its own skeleton and sensor pose, with the viewer
// camera exactly at the sensor (the colour camera's intrinsics, no distortion), rendered by
// the headless GL renderer and compared with the frame's real colour image inside the
// person's mask (image_metrics.h: each image's subject on black, PSNR and SSIM over the box of
// the union of the two silhouettes, silhouette IoU).
//
// Two recordings, both by capture::RecordClip:
//  1. every source frame, as `reenact-capture record` with the same --skeleton and --poses
//     makes it: it gives every frame's skeleton (the source's own, our depth tracker's or an
//     imported track's), person mask (the source's, else our segmentation from depth and
//     skeleton) and sensor pose (the source's, else RGB-D SLAM's), so the held-out frames and
//     the kept ones come from one skeleton track and one world frame;
//  2. the kept frames alone, given those skeletons, masks and poses as a source that knows
//     them: the stored crops, the cylinder model (radii, representative frame), the flagged
//     skeletons and every fit at load see only the kept frames.
// The reenacted clip is recording 2's frames with every excluded frame of recording 1 put back
// in its place as skeleton, pose and time only (an empty 8 x 8 crop, as the recorder stores a
// frame without the subject in view): a frame without a subject is never a texture, so the
// held-out images stay out, while the methods pose output frame k (its stored or steady
// skeleton) as they do in `reenact-eval quality`. The truth of held-out frame k is the
// source's colour image with recording 1's mask of that frame.
//
// Frames recording 1 does not store (no skeleton, or no SLAM pose) are neither kept nor
// reenacted; held-out frames among them, and held-out frames whose mask is empty, are counted
// and not compared.

#include <string>
#include <vector>

#include "common/error/expected.h"
#include "tests/eval/image_metrics.h"

namespace reenact::eval {

struct HoldoutOptions {
  std::string source;  // a frame source spec (capture::OpenFrameSource), with colour
  // The recorded skeletons, as `reenact-capture record --skeleton`: "source" (the source's
  // own; synthetic: the scene's exact ones), "track" (our depth tracker on every frame), or
  // an imported track's spec (capture::LoadSkeletonTrack: json:FILE, kinect:FILE, FILE.json).
  std::string skeleton = "source";
  bool slam_poses = false;  // SLAM even where the source knows its poses (--poses slam)
  int every = 10;           // >= 1
  int window = 0;           // >= 0
  int max_frames = -1;      // source frames read: -1 = all, else >= 1
  std::vector<std::string> methods = {"thesis"};
  // Side-by-side pictures (side_by_side.h) as PNG files in image_dir, one per method and
  // compared frame (METHOD_fNNNN.png, NNNN the source frame); none when empty.
  std::string image_dir;

  // Throws CheckError when a field is out of range.
  void Check() const;
};

// One compared frame of one method.
struct HoldoutFrame {
  std::string method;
  int source_frame = 0;    // the held-out frame
  int texture_frame = -1;  // source frame of the method's texture frame (ReenactedFrame), -1 none
  SubjectComparison comparison;
  std::string image_path;  // the picture written, if any
};

struct HoldoutRow {
  std::string method;
  int n = 0;           // frames compared
  double psnr_db = 0;  // mean over frames with finite PSNR
  double ssim = 0;     // means over the frames
  double iou = 0;
  double colour_mae = 0;  // 0..255
  // Mean |texture frame - held-out frame| in source frames, over frames with a texture frame:
  // at least W + 1.
  double texture_gap = 0;
};

struct HoldoutRun {
  std::string source;           // the source's description
  int source_frames = 0;        // read
  int recorded_frames = 0;      // recording 1: frames stored (skeleton and pose)
  int held_out = 0;             // chosen by the rule
  int excluded = 0;             // held out or within W of one
  int kept = 0;                 // recording 2's frames: the clip that textures
  int compared = 0;             // held-out frames reenacted and compared
  int lost_held_out = 0;        // held out, but without skeleton or pose in recording 1
  int empty_mask_held_out = 0;  // held out, but no person in recording 1's mask
  std::string gl_renderer;
  std::vector<HoldoutRow> rows;      // per method, in the options' order
  std::vector<HoldoutFrame> frames;  // per method, then held-out frame
};

// Errors: an unknown method ("usage", listing them); the source cannot be opened or read;
// a source without colour ("unsupported": holdout compares with the colour image; names the
// sources that have it) or whose colour camera has lens distortion ("unsupported"); the
// held-out rule's errors (holdout_frames.h, "usage"); recording 1 stores no frame (its
// error; "tracking" with the tracker's account when --skeleton track found no one); no
// held-out frame with a skeleton, pose and person ("no_frames"); no kept frame recorded
// ("usage", naming --every and --window); recording 2's errors; "gl_unavailable"; an image
// that cannot be written.
Expected<HoldoutRun> RunHoldout(const HoldoutOptions& options);

}  // namespace reenact::eval
