#pragma once
// Seeds and region growing of the person segmentation (person_segmenter.h, steps 2 and 3).

#include <cstdint>
#include <optional>
#include <vector>

#include "capture-client/segment/body_bound.h"
#include "capture-client/segment/floor_plane.h"
#include "capture-client/segment/pixel_rays.h"
#include "capture-client/segment/segment_options.h"
#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"

namespace reenact::capture {

// Per-pixel tests over one depth frame. Depth(x, y): metres, 0 for a hole or a reading
// outside [min_depth_m, max_depth_m]. BodyCandidate: a reading, inside bound.rect(), not on
// or under the floor (height above it below floor_clearance(z)), within the body bound.
class BodyPixelTest {
 public:
  // References are kept: they must outlive the test.
  BodyPixelTest(const ImageDepthMm& depth, double depth_scale_m, const PixelRays& rays,
                const BodyBound& bound, const std::optional<Plane3>& floor_in_sensor,
                const PersonSegmentOptions& options);

  double Depth(int x, int y) const {
    const double z = depth_.at(x, y) * scale_;
    return z >= min_z_ && z <= max_z_ ? z : 0.0;
  }
  bool BodyCandidate(int x, int y, double z) const;
  // Whether the reading at (x, y) with depth z > 0 lies on or under the floor.
  bool OnFloor(int x, int y, double z) const;
  // Whether the point at (x, y) with depth z lies within core_radius_m of a bone.
  bool InCore(int x, int y, double z) const;

  const BodyBound& bound() const { return bound_; }
  const PersonSegmentOptions& options() const { return options_; }

 private:
  const ImageDepthMm& depth_;
  double scale_, min_z_, max_z_;
  const PixelRays& rays_;
  const BodyBound& bound_;
  const std::optional<Plane3>& floor_;
  const PersonSegmentOptions& options_;
};

struct SeedResult {
  std::vector<int> pixels;   // y * width + x, each once
  int samples_in_image = 0;  // bone samples that fell inside the image
};

// Samples every bone of the bound every seed_step_px pixels (clipped to z >= kNearM) and
// keeps the samples whose pixel is a body candidate with a depth that agrees with the bone's
// (options' seed_in_front_m / seed_behind_m plus depth_step(z)).
SeedResult BoneSeeds(const BodyPixelTest& test, const PinholeCamera& camera);

// Grows 4-connected from the seeds across body candidates whose depth differs from the
// neighbour's by at most depth_step(z), or that lie within core_radius_m of a bone. Writes
// 255 into *mask (depth-sized, zero outside the region), its bounding box into *box, and
// returns the region's size. *state is scratch (resized as needed).
int GrowRegion(const BodyPixelTest& test, const std::vector<int>& seeds, ImageGray8* mask,
               PixelRect* box, std::vector<uint8_t>* state);

}  // namespace reenact::capture
