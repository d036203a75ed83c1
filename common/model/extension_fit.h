#pragma once
// Part extensions (cylinder_model.h's PartExtensions; issue 9, a closer shape) from a few
// stored frames: how far the subject continues past a part's end joint. Fitted for the head
// (past the head joint: the top of the head), the forearms (past the hands) and the shins
// (past the feet); every other part keeps 0.
//
// Per frame and part, with the end joint d and the other joint q of the part in the sensor
// frame (OpenCV, metres) and u = (d - q) / |d - q|: project the cylinder's front generator
// line beyond d, P(s) = d + r f + s u (f the unit direction orthogonal to u towards the
// camera: where the drawn cylinder's silhouette ends), into the image. Walk outwards from d's pixel
// along the projected axis in 1-pixel steps; at each step look at the slice across the axis within
// the part's projected radius rho = f r / z_d (r = bone length * radius ratio, f the focal length).
// A slice sample counts as the part's when the mask is subject there and the depth reading (if any)
// lies within depth_tolerance_m + r of P(s)'s depth (so a hand in front of the torso does not run
// on into the torso). The walk ends at the first slice whose counted fraction is below
// min_fill; its length L (pixels) becomes metres through the projected axis's scale at d,
// J = |d(pixel of P(s))/ds| at s = 0 (pixels per metre: the depth and the foreshortening):
// extension_m = L / J. A frame measures nothing for the part when a joint is missing or
// behind the camera, the bone is shorter than kMinBoneLength, the axis is foreshortened below
// min_axis_scale of f / z_d (points at the camera), or the walk reaches the image border
// still inside the subject. The part's ratio is the median of the frames' extension_m / bone
// length, clamped to [0, max_ratio]; 0 (and fitted false) where no frame measured.

#include <array>
#include <optional>
#include <span>

#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "common/model/cylinder_model.h"
#include "common/skeleton/skeleton.h"

namespace reenact {

struct ExtensionFitOptions {
  double min_fill = 0.3;            // (0, 1]: a slice with less of the part ends the walk
  double depth_tolerance_m = 0.05;  // >= 0, added to the radius for the depth test
  double max_ratio = 0.8;           // >= 0: extensions are clamped to [0, max_ratio]
  double min_axis_scale = 0.3;      // (0, 1]: least J / (f / z_d) a frame may measure at
  double depth_scale_m = 0.001;     // metres per depth unit, > 0

  void Check() const;
};

// One stored frame: skeleton in its sensor frame; camera, mask (255 subject) and depth
// (registered to colour, may be empty: no depth test) on the same image grid.
struct ExtensionFitFrame {
  const Skeleton* skeleton_in_sensor = nullptr;
  const PinholeCamera* camera = nullptr;
  const ImageGray8* mask = nullptr;
  const ImageDepthMm* depth = nullptr;
};

struct ExtensionFitResult {
  PartExtensions extension{};                 // ratio of bone length, 0 where not fitted
  std::array<bool, kBodyPartCount> fitted{};  // some frame measured the part
  std::array<int, kBodyPartCount> frames_measured{};
};

// The parts extension_fit measures: head, both forearms, both shins.
bool IsExtendedPart(BodyPart part);

// Extension of one part in one frame, metres past the end joint; nullopt if the frame cannot
// measure it (see above; a joint whose pixel is off the mask or outside the image too).
// Preconditions (CHECK): options valid; frame's pointers set, the mask of the camera's size, depth
// empty or of the mask's size.
std::optional<double> MeasureExtension(const ExtensionFitFrame& frame, BodyPart part,
                                       const RadiusRatios& ratios,
                                       const ExtensionFitOptions& options = {});

// The fit over frames (any number, none: every part 0, not fitted).
ExtensionFitResult FitPartExtensions(std::span<const ExtensionFitFrame> frames,
                                     const RadiusRatios& ratios,
                                     const ExtensionFitOptions& options = {});

}  // namespace reenact
