#pragma once
// The head's size measured in one depth frame of a person, for a body started without the
// calibration pose. The proportional body (BodyShape::FromHeight) gives every
// subject an average head, and the standing height then hangs the neck and the whole trunk
// below the top of the head by that average: a head larger than average puts the track's
// neck, waist and hips too high (CesiumMan's: this measurement reads 0.18 H from its top to
// its neck, against 0.097-0.12 H on the procedural body of average proportions; 10 cm).
//
// Method: the person's points within band_m of its top (heights above the floor plane, its
// normal as up) are cut into horizontal slices, each slice_m high and at least two grid rows
// at the band's depth (every slice then holds a row of points). A slice's width is the extent
// of its points across the line of sight (along up x the horizontal direction from the sensor
// to the band's centroid), which the silhouette shows whole whichever way the head faces.
// Going down from the top, the width grows to the head's widest slice, narrows at the neck
// and widens again at the shoulders. The neck is the first slice narrower than neck_ratio of
// the widest slice above it. No such slice within the band (arms raised above the head, a
// hood, the top cut off by the image's edge), a sight line along up, or no floor: no
// measurement.
//
// For a sphere of radius r seen whole, the widest slice is 2 r wide and the neck slice is the
// first below r (1 + sqrt(1 - neck_ratio^2)) from the top (1.53 r at 0.85).

#include <optional>

#include "capture-client/tracker/person_detector.h"

namespace reenact::capture {

struct HeadSizeOptions {
  double band_m = 0.45;      // how far below the top the neck is looked for, > slice_m
  double slice_m = 0.01;     // least slice height, > 0
  double neck_ratio = 0.85;  // in (0, 1)
  int min_slice_points = 3;  // slices with fewer points are skipped, >= 2

  void Check() const;
};

struct HeadSize {
  double half_width_m = 0;      // half the widest slice's width
  double neck_below_top_m = 0;  // the neck slice's middle below the top
};

// blob: a detected person; camera_fy: the focal length (pixels) of the camera whose grid the
// blob's points lie on (> 0). The head is cut by the image's edge when a point down to the
// neck lies on the grid's outermost rows or columns (blob.pixels, blob.mask's size; not
// checked when the blob has no pixel per point).
std::optional<HeadSize> MeasureHeadSize(const PersonBlob& blob, double camera_fy,
                                        const HeadSizeOptions& options = {});

}  // namespace reenact::capture
