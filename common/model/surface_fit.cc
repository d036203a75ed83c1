#include "common/model/surface_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "common/error/check.h"
#include "common/estimate/median.h"
#include "common/render/cylinder_mesh.h"

namespace reenact {

namespace {

struct SurfacePoint {
  int frame = 0;
  double t = 0;
  double phi = 0;    // [-pi, pi]
  double rho = 0;    // normalised radial coordinate
  double scale = 0;  // metres per unit of rho here: r sqrt(W(t) D(t))
};

using PartPoints = std::array<std::vector<SurfacePoint>, kBodyPartCount>;

void CheckFrame(const SurfaceFitFrame& frame) {
  REENACT_CHECK(frame.skeleton_in_sensor && frame.camera && frame.mask && frame.depth,
                "a surface fit frame needs its skeleton, camera, mask and depth");
  const ImageGray8& mask = *frame.mask;
  REENACT_CHECK(mask.channels == 1 && mask.width == frame.camera->width &&
                    mask.height == frame.camera->height,
                "mask must be 1-channel of the camera's size");
  const ImageDepthMm& depth = *frame.depth;
  REENACT_CHECK(depth.empty() || (depth.channels == 1 && depth.width == mask.width &&
                                  depth.height == mask.height),
                "depth must be empty or 1-channel of the mask's size");
}

// The points of one frame, each given to the part whose ring surface lies nearest.
void CollectPoints(const SurfaceFitFrame& frame, int frame_index, const RadiusRatios& ratios,
                   const PartExtensions& extensions, const PartShapes& shapes,
                   const SurfaceFitOptions& options, PartPoints& points) {
  const ImageDepthMm& depth = *frame.depth;
  if (depth.empty()) return;
  struct Posed {
    Eigen::Matrix4d unit_from_sensor;
    double radius = 0;
    const PartShape* shape = nullptr;
  };
  std::array<std::optional<Posed>, kBodyPartCount> posed;
  for (int p = 0; p < kBodyPartCount; ++p) {
    const auto part = static_cast<BodyPart>(p);
    std::optional<Cylinder> c =
        PoseCylinder(*frame.skeleton_in_sensor, part, ratios, extensions, shapes);
    if (!c || !(c->radius > 0)) continue;
    const auto reference = PartReferenceDirection(*frame.skeleton_in_sensor, part);
    if (!reference) continue;
    c->width_direction = reference;
    posed[p] = Posed{ViewerFromUnitCylinder(*c).inverse(), c->radius, &shapes[p]};
  }
  const PinholeCamera& camera = *frame.camera;
  const ImageGray8& mask = *frame.mask;
  for (int y = 0; y < mask.height; y += options.pixel_step) {
    for (int x = 0; x < mask.width; x += options.pixel_step) {
      if (mask.at(x, y) < 128 || depth.at(x, y) == 0) continue;
      const Eigen::Vector3d point =
          camera.Unproject(Eigen::Vector2d(x, y), depth.at(x, y) * options.depth_scale_m);
      std::optional<SurfacePoint> best;
      int best_part = -1;
      double best_distance = std::numeric_limits<double>::infinity();
      for (int p = 0; p < kBodyPartCount; ++p) {
        if (!posed[p]) continue;
        const Eigen::Vector3d q = (posed[p]->unit_from_sensor * point.homogeneous()).head<3>();
        if (!(q.z() >= 0 && q.z() <= 1)) continue;
        const double w = RingValueAt(posed[p]->shape->width, q.z());
        const double d = RingValueAt(posed[p]->shape->depth, q.z());
        const Eigen::Vector2d e(q.x() / w, q.y() / d);
        const double rho = e.norm();
        const double scale = posed[p]->radius * std::sqrt(w * d);
        const double distance = std::abs(rho - 1) * scale;
        if (distance < best_distance) {
          best_distance = distance;
          best_part = p;
          best = SurfacePoint{frame_index, q.z(), std::atan2(e.y(), e.x()), rho, scale};
        }
      }
      if (best && best->rho >= options.min_factor && best->rho <= options.max_factor)
        points[best_part].push_back(*best);
    }
  }
}

int NearestRing(double t) {
  return std::clamp(static_cast<int>(std::lround(t * (kShapeRings - 1))), 0, kShapeRings - 1);
}

int NearestNode(double phi, int angles) {
  const double x = phi / (2 * std::numbers::pi) * angles;
  return ((static_cast<int>(std::lround(x)) % angles) + angles) % angles;
}

// The surface of `angles` nodes from the points whose frame passes `use` (see the header's
// Cells).
template <typename Use>
PartSurface FitSurface(const std::vector<SurfacePoint>& points, int angles, const Use& use,
                       const SurfaceFitOptions& options) {
  PartSurface surface;
  surface.angles = angles;
  std::array<std::array<std::vector<double>, kMaxSurfaceAngles>, kShapeRings> rho;
  std::array<std::array<std::vector<int>, kMaxSurfaceAngles>, kShapeRings> frames;
  for (const SurfacePoint& point : points) {
    if (!use(point.frame)) continue;
    const int k = NearestRing(point.t), j = NearestNode(point.phi, angles);
    rho[k][j].push_back(point.rho);
    frames[k][j].push_back(point.frame);
  }
  std::array<std::array<bool, kMaxSurfaceAngles>, kShapeRings> measured{};
  for (int k = 0; k < kShapeRings; ++k)
    for (int j = 0; j < angles; ++j) {
      std::vector<int>& f = frames[k][j];
      std::sort(f.begin(), f.end());
      const auto distinct = std::unique(f.begin(), f.end()) - f.begin();
      measured[k][j] = static_cast<int>(rho[k][j].size()) >= options.min_points &&
                       distinct >= options.min_frames;
      surface.radial[k][j] = measured[k][j] ? Median(rho[k][j]) : 1.0;
    }
  auto filled = measured;
  for (int k = 0; k < kShapeRings; ++k)
    for (int j = 0; j < angles; ++j) {
      const int before = (j + angles - 1) % angles, after = (j + 1) % angles;
      if (measured[k][j] || !measured[k][before] || !measured[k][after]) continue;
      surface.radial[k][j] = 0.5 * (surface.radial[k][before] + surface.radial[k][after]);
      filled[k][j] = true;
    }
  const auto along = surface.radial;
  for (int k = 0; k < kShapeRings; ++k)
    for (int j = 0; j < angles; ++j) {
      if (filled[k][j]) continue;
      double sum = 0;
      int count = 0;
      for (int n : {k - 1, k + 1})
        if (n >= 0 && n < kShapeRings && filled[n][j]) {
          sum += along[n][j];
          ++count;
        }
      if (count > 0) surface.radial[k][j] = sum / count;
    }
  return surface;
}

// rho of the drawn surface at (t, phi): linear between the rings and the nodes.
double ModelRho(const PartSurface& surface, double t, double phi) {
  if (surface.IsEmpty()) return 1.0;
  const double x = std::clamp(t, 0.0, 1.0) * (kShapeRings - 1);
  const int k = std::min(kShapeRings - 2, static_cast<int>(x));
  const double f = x - k;
  return (1 - f) * surface.FactorAt(k, phi) + f * surface.FactorAt(k + 1, phi);
}

// Held-out error of one resolution (0: the rings alone), metres; nullopt where a half has no
// point.
std::optional<double> HeldOutError(const std::vector<SurfacePoint>& points, int angles,
                                   const std::vector<int>& half_of_frame,
                                   const SurfaceFitOptions& options) {
  double sum = 0;
  int count = 0;
  std::array<int, 2> per_half{};
  for (int half = 0; half < 2; ++half) {
    const auto train = [&](int frame) { return half_of_frame[frame] != half; };
    const PartSurface surface =
        angles == 0 ? PartSurface{} : FitSurface(points, angles, train, options);
    for (const SurfacePoint& point : points) {
      if (train(point.frame)) continue;
      sum += std::abs(point.rho - ModelRho(surface, point.t, point.phi)) * point.scale;
      ++count;
      ++per_half[half];
    }
  }
  if (per_half[0] == 0 || per_half[1] == 0) return std::nullopt;
  return sum / count;
}

}  // namespace

void SurfaceFitOptions::Check() const {
  REENACT_CHECK(!angle_choices.empty(), "angle_choices must not be empty");
  for (size_t i = 0; i < angle_choices.size(); ++i)
    REENACT_CHECK(angle_choices[i] >= 3 && angle_choices[i] <= kMaxSurfaceAngles &&
                      (i == 0 || angle_choices[i] > angle_choices[i - 1]),
                  "angle_choices must increase, each in [3, kMaxSurfaceAngles]");
  REENACT_CHECK(min_points >= 1, "min_points must be >= 1");
  REENACT_CHECK(min_frames >= 1, "min_frames must be >= 1");
  REENACT_CHECK(min_factor > 0 && min_factor <= 1, "min_factor must be in (0, 1]");
  REENACT_CHECK(std::isfinite(max_factor) && max_factor >= 1, "max_factor must be >= 1");
  REENACT_CHECK(min_gain >= 0 && min_gain < 1, "min_gain must be in [0, 1)");
  REENACT_CHECK(pixel_step >= 1, "pixel_step must be >= 1");
  REENACT_CHECK(std::isfinite(depth_scale_m) && depth_scale_m > 0, "depth_scale_m must be > 0");
}

SurfaceFitResult FitPartSurfaces(std::span<const SurfaceFitFrame> frames,
                                 const RadiusRatios& ratios, const PartExtensions& extensions,
                                 const PartShapes& shapes, const SurfaceFitOptions& options) {
  options.Check();
  for (const PartShape& shape : shapes)
    REENACT_CHECK(shape.surface.IsEmpty(), "the shapes to fit a surface on must have none");
  PartPoints points;
  for (size_t n = 0; n < frames.size(); ++n) {
    CheckFrame(frames[n]);
    CollectPoints(frames[n], static_cast<int>(n), ratios, extensions, shapes, options, points);
  }
  std::vector<int> half_of_frame(frames.size());
  for (size_t n = 0; n < frames.size(); ++n) half_of_frame[n] = static_cast<int>(n % 2);

  SurfaceFitResult result;
  result.shape = shapes;
  for (BodyPart limb : {BodyPart::kLeftUpperArm, BodyPart::kRightUpperArm, BodyPart::kLeftThigh,
                        BodyPart::kRightThigh})
    result.shape[Index(limb)].round_end = {true, true};
  for (BodyPart limb : {BodyPart::kLeftForearm, BodyPart::kRightForearm, BodyPart::kLeftShin,
                        BodyPart::kRightShin})
    result.shape[Index(limb)].round_end = {true, false};
  for (int p = 0; p < kBodyPartCount; ++p) {
    result.points[p] = static_cast<int>(points[p].size());
    const auto rings_error = HeldOutError(points[p], 0, half_of_frame, options);
    if (!rings_error) continue;
    int chosen = 0;
    double chosen_error = *rings_error;
    for (int angles : options.angle_choices) {
      const double error = *HeldOutError(points[p], angles, half_of_frame, options);
      if (error < (1 - options.min_gain) * chosen_error) {
        chosen = angles;
        chosen_error = error;
      }
    }
    result.scored[p] = true;
    result.rings_error_m[p] = *rings_error;
    result.chosen_error_m[p] = chosen_error;
    result.angles[p] = chosen;
    if (chosen > 0)
      result.shape[p].surface =
          FitSurface(points[p], chosen, [](int) { return true; }, options);
  }
  return result;
}

}  // namespace reenact
