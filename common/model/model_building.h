#pragma once
// Building the cylinder body model of a whole clip (thesis Sec. 3.3.3, Eq. 2-4):
//   1. F(n) (Eq. 2, representative_frame.h) for every frame's skeleton in its sensor frame;
//      frames are ranked by F(n), highest first, ties to the earlier frame.
//   2. The thesis fits the radius ratios on n^ = argmax_n F(n) (Eq. 4) alone (robust_k = 1).
//      With robust_k = k > 1, the ratios are fitted on each of the k best-ranked frames and
//      each part takes the median of its fitted ratios, so one frame with a bad mask, a
//      depth glitch or a misplaced joint cannot set the model alone (use an odd k: with an
//      even count the median is the mean of the two middle values).
//   3. Each frame's fit is FitRadiusRatios (radius_fit.h) on that frame's depth, mask and
//      camera, fetched through a callback so that a long clip never has to sit in memory.
// A frame whose images the callback cannot give, or gives with sizes that disagree with
// each other or the camera, is skipped and the next-ranked frame takes its place.
// A part that is not fitted keeps DefaultRadiusRatios() and says why (PartFitOutcome).
// Nothing here throws on bad data: every joint missing, zero-length or sub-millimetre bones,
// empty masks and depth holes end as parts that kept their default.

#include <array>
#include <functional>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "common/model/cylinder_model.h"
#include "common/model/radius_fit.h"
#include "common/model/representative_frame.h"
#include "common/skeleton/skeleton.h"

namespace reenact {

// One frame's images, as radius_fit.h wants them: depth registered to the mask's grid and
// camera is the camera of that grid (e.g. PinholeCamera::Cropped for a subject crop).
struct ModelFrameImages {
  PinholeCamera camera;
  ImageDepthMm depth;
  ImageGray8 mask;  // 255 = subject
};

// Gives frame n's images, or nullopt if they cannot be had (the frame is then skipped).
using ModelFrameImagesFn = std::function<std::optional<ModelFrameImages>(int frame)>;

struct ModelBuildOptions {
  RepresentativeFrameOptions representative;  // Eq. 2 weights
  RadiusFitOptions fit;                       // per-frame rectangle fit
  // Frames fitted, best F(n) first; 1 is the thesis's single representative frame. >= 1.
  int robust_k = 1;
  // A part needs a fit in at least this many of the fitted frames, else it keeps its
  // default. [1, robust_k]. Default 1.
  int min_part_fits = 1;
  // Fitted ratios outside (0, max_ratio] are implausible (a radius more than twice the bone
  // length; the manifest rejects them) and are dropped for that frame. > 0. Default 2.
  double max_ratio = 2.0;
  // Frames skipped because their images were unavailable before giving up, >= 0.
  // Default 16.
  int max_skipped_frames = 16;

  void Check() const;
};

// Why a part has the ratio it has. kMissingJoint .. kImplausible: the part was kept in no
// fitted frame, and this is why it failed in the best-ranked fitted frame.
enum class PartFitOutcome {
  kFitted = 0,    // the median of its kept ratios
  kNoFrame,       // no frame could be scored and fetched: nothing was fitted at all
  kMissingJoint,  // a joint of the part is missing
  kShortBone,     // the bone is shorter than kMinBoneLength, or than 2 pixels in the image
  kNoPixels,      // no subject pixel went to it (empty mask, off the image, behind it)
  kTooFewSlices,  // pixels, but fewer than RadiusFitOptions::min_slices valid slices, or
                  // not one depth reading among them
  kImplausible,   // fitted, but the ratio lies outside (0, max_ratio]
  kTooFewFits,    // kept in some frames, but fewer than min_part_fits
};
std::string_view PartFitOutcomeName(PartFitOutcome outcome);  // "fitted", "no_frame", ...

struct ModelBuildResult {
  // The thesis's n^: the best-ranked frame that was fitted (argmax F(n) of Eq. 4 unless its
  // images were unavailable); nullopt if no frame was fitted.
  std::optional<int> representative_frame;
  std::vector<int> fitted_frames;    // frames fitted, best F(n) first (size <= robust_k)
  std::vector<double> frame_scores;  // F(n) of each fitted frame, same order
  std::vector<int> skipped_frames;   // ranked frames skipped for unavailable or bad images
  RadiusRatios radius_ratio{};       // fitted or DefaultRadiusRatios()
  std::array<bool, kBodyPartCount> fitted{};
  std::array<int, kBodyPartCount> fit_count{};  // frames whose fit of the part was kept
  std::array<PartFitOutcome, kBodyPartCount> outcome{};

  int fitted_count() const;
};

// skeletons_in_sensor: one skeleton per frame, each in its own sensor frame. usable (if not
// empty): one flag per frame, false frames are never chosen. images: see ModelFrameImagesFn.
ModelBuildResult BuildCylinderModel(std::span<const Skeleton> skeletons_in_sensor,
                                    const ModelFrameImagesFn& images,
                                    const ModelBuildOptions& options = {},
                                    std::span<const bool> usable = {});

}  // namespace reenact
