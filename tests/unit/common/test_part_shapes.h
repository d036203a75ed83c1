#pragma once
// Test support: part shapes (cylinder_model.h's PartShape) used as ground truth by the shaped
// rendering, labelling and fitting tests.

#include <array>

#include "common/model/cylinder_model.h"

namespace reenact::testing {

// Ring values growing linearly from `first` at t = 0 to `last` at t = 1.
inline std::array<double, kShapeRings> LinearRings(double first, double last) {
  std::array<double, kShapeRings> rings{};
  for (int k = 0; k < kShapeRings; ++k)
    rings[k] = first + (last - first) * k / (kShapeRings - 1);
  return rings;
}

// The same ellipse (width x depth, ratios of the radius) at every ring.
inline PartShape Uniform(double width, double depth) {
  PartShape shape;
  shape.width.fill(width);
  shape.depth.fill(depth);
  return shape;
}

// A circular cone frustum: rings from `from` at a to `to` at b.
inline PartShape Cone(double from, double to) {
  PartShape shape;
  shape.width = shape.depth = LinearRings(from, to);
  return shape;
}

}  // namespace reenact::testing
