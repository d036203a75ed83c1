#pragma once
// Named texturing settings (reenactment.h's TexturingOptions), each adding one step of issue 9
// to the one before; `reenact-viewer play --texturing NAME` and `reenact-eval quality`'s
// methods use the same names:
//   thesis     whole-body Eq. 5, one frame, no occlusion handling
//   per-part   per-part selection (common/texture/part_selection.h), one frame per part
//   occlusion  per-part, the 3 best frames per part, the first visible one per fragment
//   blend      per-part, the visible ones of the 3 best blended by weight, hysteresis 0.1
//   shape      blend with the parts extended past their end joints (BodyShape::kExtended)
//   profile    shape with radius rings along every part and an elliptic torso
//              (BodyShape::kProfiled)
//   relit      profile with every stored colour relit from its recorded pose to the shown one
//              under the clip's fitted subject light (TexturingOptions::relight)
//   fallback   relit with 3 fallback candidates per part, chosen to see what of the part the
//              3 ranked ones do not (TexturingOptions::fallback_candidates)
//   surface    fallback with each part's surface fitted from the stored depth around its axis
//              as well as along it, textured through the part's body-fixed frame
//              (BodyShape::kSurface)

#include <string>
#include <string_view>

#include "common/error/expected.h"
#include "viewer-client/play/reenactment.h"

namespace reenact::viewer {

// The viewer's default (reenact-viewer play, reenact-bench viewer): the step with the best PSNR,
// SSIM, silhouette IoU and seen-part rate at every view (reenact-eval quality on CesiumMan and
// the procedural body; its drawn-part rate is above fallback's, see docs/measurements.md), with
// the whole AR loop above 30 fps.
inline constexpr std::string_view kDefaultTexturingPreset = "surface";

// The names above, in that order, comma separated (for usage messages).
std::string TexturingPresetNames();

// The preset of that name; error "usage" naming the known presets otherwise.
Expected<TexturingOptions> TexturingPreset(std::string_view name);

}  // namespace reenact::viewer
