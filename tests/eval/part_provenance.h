#pragma once
// The wrong-part rate of a reenacted frame: which share of the rendered subject's colour was
// taken from source pixels that the source frame's ground-truth part labels assign to another
// body part or to the background (the thesis's doubled-limb failure: a forearm textured with
// torso pixels, a leg with the other leg's).
//
// Provenance is exact: it is read from the CPU reference renderer's per-pixel output for the
// draw list (common/render/reference_renderer.h): `part` (index of the cylinder that drew the
// pixel) and, per contributing texture candidate j (one, or several where candidates are
// blended), `source_frame` j, `source_pixel` (u_j, v_j) in that stored crop's pixels and
// `source_weight` c_j (the contributor's normalised share of the colour, summing to 1; a
// render without source_weight counts channel 0 with share 1). The colour at
// (u, v) is the renderer's bilinear blend of the four nearest texels (clamped to the crop's
// edge) whose crop mask is >= 128 (alpha 1), each weighted by its bilinear weight w_i and
// normalised by their sum. A pixel's wrong share is
//   sum_i w_i [label_i != PartLabel(part of the cylinder)] / sum_i w_i    (over alpha-1 texels)
// with label_i the source frame's label image at the texel's sensor pixel (crop pixel +
// the crop's offset; 0 = background outside the label image). A pixel sampled wholly from
// the right part counts 0, wholly from another part 1, half-way across a border 1/2. A
// blended pixel's wrong share is the shares' weighted sum, sum_j c_j wrong_j: two equally
// weighted candidates, one wholly right and one wholly wrong, count 1/2.
//
//   wrong_part_rate = sum of wrong shares / subject pixels
//
// That rate asks for the drawn cylinder's part, so it also counts the model's part borders
// against the body's: where the upper-torso cylinder covers what the body's skinning calls the
// lower torso, a pixel copied from exactly what the sensor saw there counts as wrong (at the
// sensor's own view with frame k itself stored, the reenactment is such a copy and still
// scores 0.09 on CesiumMan). The seen-part rate asks instead for the part the ground truth
// shows at the output pixel, from the same camera:
//
//   wrong_seen_part_rate = sum of wrong shares against seen_label(x, y) / subject pixels
//
// with seen_label(x, y) the truth's label at the pixel, or the drawn cylinder's part where
// the truth shows no subject there (an extra pixel: a silhouette error, which the IoU
// measures). It is 0 for a pixel copy of the right view (up to bilinear sampling across
// label borders) and counts what the viewer sees as another part's texture where the body
// shows this one. Its wrong shares are of two kinds: where the drawn cylinder is not the part
// the truth shows (the model's geometry: where its cylinders stand against the body's parts,
// which no choice of texture changes), and where it is, so that only the texture came from
// another part (the texturing's own error):
//
//   wrong_texture_rate = sum of wrong shares against seen_label(x, y) over the pixels where
//                        the truth shows the drawn part / subject pixels
//
// Both rates count a texel a few centimetres across a part border as wrong: a seam that the
// cylinders' texture mapping places a little off the body's border, or the model's part
// borders against the skinning's (at an upper / lower torso border on one shirt nobody sees a
// wrong part). What the thesis's viewers saw was a doubled limb: another part's texture where
// that part is nowhere near. The doubled-limb rate counts only that:
//
//   doubled_limb_rate = sum over textured pixels and contributors j of
//                       c_j sum_i w_i [label_i is a body part != seen_label(x, y) and the
//                       truth shows label_i nowhere within r(x, y) of (x, y)] / sum_i w_i,
//                       divided by the subject pixels
//
// with r(x, y) = focal_px border_m / z(x, y) pixels, border_m (default 5 cm) on the shown
// surface at the render's depth z there, and the distance the Euclidean one in the image to
// the nearest pixel the truth labels label_i. It is at most the seen-part rate; background
// texels (a silhouette error) do not count.
//
// Subject pixels are all pixels the reference render marks (mask 255); a pixel drawn in a
// part's flat colour (no stored frame: untextured) took no colour from any source pixel and
// counts as subject but never as wrong; their share is reported as untextured_rate.

#include <functional>
#include <span>

#include "common/image/image.h"
#include "common/render/reference_renderer.h"
#include "common/skeleton/skeleton.h"

namespace reenact::eval {

// What the renderer sampled from one stored frame, and its ground-truth labels.
struct SourceLabels {
  const ImageGray8* crop_mask = nullptr;  // the crop's mask as uploaded (>= 128 = alpha 1)
  int crop_x = 0;                         // the crop's top-left pixel in the sensor image
  int crop_y = 0;
  const ImageLabel8* labels = nullptr;  // the sensor image's part labels (PartLabel or 0)
};

struct PartProvenance {
  int subject_pixels = 0;   // pixels the reference render marks as subject
  int textured_pixels = 0;  // of those, coloured from a stored frame
  double wrong_pixels = 0;  // sum of the textured pixels' wrong shares
  // The same against the part the ground truth shows at the pixel (0 unless measured).
  double wrong_seen_pixels = 0;
  // Of those, the pixels where the truth shows the drawn part (0 unless measured).
  double wrong_texture_pixels = 0;
  // The doubled-limb shares (above; 0 unless measured).
  double doubled_limb_pixels = 0;
  double WrongPartRate() const { return subject_pixels ? wrong_pixels / subject_pixels : 0.0; }
  double WrongSeenPartRate() const {
    return subject_pixels ? wrong_seen_pixels / subject_pixels : 0.0;
  }
  double WrongTextureRate() const {
    return subject_pixels ? wrong_texture_pixels / subject_pixels : 0.0;
  }
  double DoubledLimbRate() const {
    return subject_pixels ? doubled_limb_pixels / subject_pixels : 0.0;
  }
  double UntexturedRate() const {
    return subject_pixels ? 1.0 - static_cast<double>(textured_pixels) / subject_pixels : 0.0;
  }
};

// Default border of the doubled-limb rate, metres on the shown surface.
inline constexpr double kDoubledLimbBorderM = 0.05;

// The ground truth as seen from the render's camera, for the seen-part and doubled-limb rates.
struct SeenParts {
  const ImageLabel8* labels = nullptr;    // its part labels (PartLabel or 0), the render's size
  double focal_px = 0;                    // the render camera's focal length, pixels; > 0
  double border_m = kDoubledLimbBorderM;  // finite, >= 0
};

// The wrong share of one sample at crop pixel (u, v) for the expected label (see above);
// 0 when no texel there has alpha 1 (the renderer would have discarded the fragment).
double WrongShareOfSample(const SourceLabels& source, double u, double v, int expected_label);

// Sums the wrong shares over a reference render. cylinder_parts[i] is the body part of the
// render's part index i; source(n) gives stored frame n's crop mask and labels (called once
// per contributor of a textured pixel; it may cache). seen: the ground truth from the render's
// camera, for wrong_seen_pixels, wrong_texture_pixels and doubled_limb_pixels; null leaves
// them 0. Preconditions (CHECK): every part index in the render is < cylinder_parts.size();
// source(n) returns non-null images for every source frame; seen, when given, has labels of
// the render's size, focal_px > 0 and border_m >= 0, both finite.
PartProvenance MeasurePartProvenance(const ReferenceRender& render,
                                     std::span<const BodyPart> cylinder_parts,
                                     const std::function<SourceLabels(int frame)>& source,
                                     const SeenParts* seen = nullptr);

}  // namespace reenact::eval
