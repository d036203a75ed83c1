#include "common/model/cross_section_fit.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "common/error/check.h"
#include "common/estimate/median.h"
#include "common/model/part_pixel_assignment.h"

namespace reenact {
namespace {

// Step along the 3D axis used to find the projected axis's scale, metres.
constexpr double kAxisStepM = 0.01;
// Pixel labels of the assignment pass (>= 0: counted for that part).
constexpr int8_t kBackground = -1;
constexpr int8_t kNotCounted = -2;

double RingT(int k) { return static_cast<double>(k) / (kShapeRings - 1); }

// Where ring k is measured along the drawn axis.
double MeasuredT(int k, const CrossSectionFitOptions& options) {
  if (k == 0) return options.end_inset;
  if (k == kShapeRings - 1) return 1 - options.end_inset;
  return RingT(k);
}

// A ring's slice: 1-pixel lines across the projected axis between v_lo and v_lo + lines
// (v: pixels along the projected axis from its a end).
struct RingSlice {
  bool usable = false;
  double t = 0;
  Eigen::Vector3d centre;  // on the drawn axis, camera frame
  double v_centre = 0, v_lo = 0;
  int lines = 0;
};

// A counted pixel of a line: its signed offset across the axis (pixels) and where it is.
struct LinePixel {
  double offset;
  int x, y;
};

struct PartGeometry {
  bool measurable = false;
  Cylinder cylinder;
  Eigen::Vector3d u;  // unit axis a -> b
  std::optional<Eigen::Vector3d> width_direction;
  std::array<RingSlice, kShapeRings> slices{};
  std::array<std::vector<std::vector<LinePixel>>, kShapeRings> lines{};
};

double AlongAxis(const ProjectedPartAxis& axis, const Eigen::Vector2d& pixel) {
  return (pixel - axis.a).dot(axis.dir);
}

// Depth of the 3D axis point seen at image parameter t of the projected axis (the
// perspective inverse of the segment's projection).
double AxisDepthAt(double t, double z_a, double z_b) {
  const double tau = t * z_a / (t * z_a + (1 - t) * z_b);
  return (1 - tau) * z_a + tau * z_b;
}

// The signed distance from the axis to the tangent plane through the camera centre and the
// edge pixel's ray, measured towards the side `side_in_3d` (and the plane's unit normal
// oriented that way); nullopt if the ray runs parallel to the axis.
struct EdgeSupport {
  double h = 0;
  Eigen::Vector3d normal;
};

std::optional<EdgeSupport> SupportAtEdge(const PinholeCamera& camera, const Eigen::Vector2d& pixel,
                                         const Eigen::Vector3d& point_on_axis,
                                         const Eigen::Vector3d& u,
                                         const Eigen::Vector3d& side_in_3d) {
  const Eigen::Vector3d ray = camera.Unproject(pixel, 1.0);
  Eigen::Vector3d n = ray.cross(u);
  const double norm = n.norm();
  if (!(norm > 1e-12 * ray.norm())) return std::nullopt;
  n /= norm;
  if (n.dot(side_in_3d) < 0) n = -n;
  return EdgeSupport{-point_on_axis.dot(n), n};
}

// Whether a line's outermost pixel (x, y) of `part` on one side is a silhouette edge: the
// pixel one step further out across the axis is background or the part's own, or lies more
// than `gap_m` behind it (the part occludes what is there); and neither lies on or past the
// image border.
struct EdgeTest {
  const Image<int8_t>& labels;
  const ImageDepthMm& depth;
  double depth_scale_m;
  double gap_m;

  bool operator()(int x, int y, const Eigen::Vector2d& outward, int part) const {
    if (x <= 0 || y <= 0 || x >= labels.width - 1 || y >= labels.height - 1) return false;
    const int ox = static_cast<int>(std::lround(x + outward.x()));
    const int oy = static_cast<int>(std::lround(y + outward.y()));
    if (!labels.Contains(ox, oy)) return false;
    const int8_t label = labels.at(ox, oy);
    if (label == kBackground || label == part) return true;
    return !depth.empty() && depth.at(x, y) != 0 && depth.at(ox, oy) != 0 &&
           (depth.at(ox, oy) - depth.at(x, y)) * depth_scale_m > gap_m;
  }
};

// How far (pixels, along `outward`: the projected axis's direction away from the part) the
// rim of the disc of radius r that closes the axis at `end` reaches past end's pixel: the
// near rim of an end seen in perspective. 0 if some rim point is not in front of the camera.
double EndRimBand(const PinholeCamera& camera, const Eigen::Vector3d& end,
                  const Eigen::Vector3d& other, double radius, const Eigen::Vector2d& outward) {
  const Eigen::Vector3d u = (end - other).normalized();
  const Eigen::Vector3d e1 = u.unitOrthogonal(), e2 = u.cross(e1);
  const auto end_px = camera.Project(end);
  if (!end_px) return 0;
  double band = 0;
  constexpr int kRimPoints = 16;
  for (int i = 0; i < kRimPoints; ++i) {
    const double phi = 2 * std::numbers::pi * i / kRimPoints;
    const auto px = camera.Project(end + radius * (std::cos(phi) * e1 + std::sin(phi) * e2));
    if (!px) return 0;
    band = std::max(band, (*px - *end_px).dot(outward));
  }
  return band;
}

// The run of a line's pixels that is the part's silhouette across the axis: the pixels sorted
// by offset, split where the gap between neighbours holds background (a gap of other parts'
// or rejected pixels is an occluder in front and is bridged), and of those runs the one that
// contains the axis or else lies nearest to it. Returns its outermost pixels (lower, upper
// offset); nullopt for an empty line.
std::optional<std::pair<LinePixel, LinePixel>> AxisRun(std::vector<LinePixel>& pixels,
                                                       const Image<int8_t>& labels,
                                                       const ProjectedPartAxis& axis, double v) {
  if (pixels.empty()) return std::nullopt;
  std::sort(pixels.begin(), pixels.end(),
            [](const LinePixel& l, const LinePixel& r) { return l.offset < r.offset; });
  const auto background_between = [&](double from, double to) {
    for (double s = from + 0.5; s < to; s += 0.5) {
      const Eigen::Vector2d p = axis.a + v * axis.dir + s * axis.normal;
      const int x = static_cast<int>(std::lround(p.x())), y = static_cast<int>(std::lround(p.y()));
      if (labels.Contains(x, y) && labels.at(x, y) == kBackground) return true;
    }
    return false;
  };
  std::optional<std::pair<LinePixel, LinePixel>> best;
  double best_distance = std::numeric_limits<double>::infinity();
  size_t begin = 0;
  for (size_t i = 1; i <= pixels.size(); ++i) {
    if (i < pixels.size() && (pixels[i].offset - pixels[i - 1].offset <= 1.0 ||
                              !background_between(pixels[i - 1].offset, pixels[i].offset)))
      continue;
    const LinePixel& lo = pixels[begin];
    const LinePixel& hi = pixels[i - 1];
    const double distance = lo.offset > 0 ? lo.offset : hi.offset < 0 ? -hi.offset : 0.0;
    if (distance < best_distance) {
      best_distance = distance;
      best = std::make_pair(lo, hi);
    }
    begin = i;
  }
  return best;
}

// Rings without a value take the value interpolated linearly (in their measured positions)
// between the nearest rings that have one, or copied beyond the outermost. Precondition: some
// ring has a value.
std::array<double, kShapeRings> FillRings(
    const std::array<std::optional<double>, kShapeRings>& measured,
    const CrossSectionFitOptions& options) {
  std::array<double, kShapeRings> out{};
  for (int k = 0; k < kShapeRings; ++k) {
    if (measured[k]) {
      out[k] = *measured[k];
      continue;
    }
    int lo = k - 1, hi = k + 1;
    while (lo >= 0 && !measured[lo]) --lo;
    while (hi < kShapeRings && !measured[hi]) ++hi;
    if (lo >= 0 && hi < kShapeRings) {
      const double tl = MeasuredT(lo, options), th = MeasuredT(hi, options);
      const double f = (MeasuredT(k, options) - tl) / (th - tl);
      out[k] = (1 - f) * *measured[lo] + f * *measured[hi];
    } else {
      out[k] = lo >= 0 ? *measured[lo] : *measured[hi];
    }
  }
  return out;
}

// Fills rings no frame measured and extrapolates the end rings (see the header). measured[k]
// holds the value at MeasuredT(k).
std::array<double, kShapeRings> CompleteRings(
    const std::array<std::optional<double>, kShapeRings>& measured,
    const CrossSectionFitOptions& options) {
  std::array<double, kShapeRings> out = FillRings(measured, options);
  if (options.extrapolate_end_rings) {
    const int last = kShapeRings - 1;
    // Weight of the end ring at its measured position under linear interpolation.
    const double w0 = (RingT(1) - MeasuredT(0, options)) / (RingT(1) - RingT(0));
    const double w_last =
        (MeasuredT(last, options) - RingT(last - 1)) / (RingT(last) - RingT(last - 1));
    if (measured[0]) out[0] = out[1] + (*measured[0] - out[1]) / w0;
    if (measured[last]) out[last] = out[last - 1] + (*measured[last] - out[last - 1]) / w_last;
  }
  for (double& v : out) v = std::clamp(v, options.min_ratio, options.max_ratio);
  return out;
}

struct RingFit {
  double width = 1, depth = 1;
  bool elliptic = false;
};

// A torso ring whose frames cannot separate W and D, given the width and depth of the
// part's rings that could (interpolated to this ring): if most of its frames see it frontally,
// D is taken over and each frontal frame's q^2 = W^2 c + D^2 (1 - c) gives W, else W is taken
// over and each side frame gives D; the median over those frames is taken. nullopt if none of
// its frames has a width direction.
std::optional<RingFit> FitRingWithOtherAxis(const std::vector<RingMeasurement>& samples,
                                            double width, double depth,
                                            const CrossSectionFitOptions& options) {
  std::vector<double> frontal, side;  // (c, q^2) as c, then q^2
  std::vector<std::pair<double, double>> rows;
  for (const RingMeasurement& m : samples)
    if (m.width_weight)
      rows.emplace_back(0.5 * ((*m.width_weight)[0] + (*m.width_weight)[1]),
                        m.half_width * m.half_width);
  if (rows.empty()) return std::nullopt;
  const long frontal_count = std::count_if(
      rows.begin(), rows.end(), [&](const auto& r) { return r.first >= options.elliptic_split; });
  const bool solve_width = 2 * frontal_count >= static_cast<long>(rows.size());
  const double lo = options.min_ratio * options.min_ratio;
  const double hi = options.max_ratio * options.max_ratio;
  std::vector<double> solved;
  for (const auto& [c, y] : rows) {
    if (solve_width && c >= options.elliptic_split)
      solved.push_back(std::sqrt(std::clamp((y - depth * depth * (1 - c)) / c, lo, hi)));
    if (!solve_width && c < options.elliptic_split)
      solved.push_back(std::sqrt(std::clamp((y - width * width * c) / (1 - c), lo, hi)));
  }
  RingFit fit;
  fit.width = solve_width ? Median(solved) : width;
  fit.depth = solve_width ? depth : Median(solved);
  return fit;
}

// One ring over frames (see the header).
RingFit FitRing(const std::vector<RingMeasurement>& samples,
                const CrossSectionFitOptions& options) {
  std::vector<double> q, c, y;
  for (const RingMeasurement& m : samples) {
    q.push_back(m.half_width);
    if (m.width_weight) {
      c.push_back(0.5 * ((*m.width_weight)[0] + (*m.width_weight)[1]));
      y.push_back(m.half_width * m.half_width);
    }
  }
  RingFit fit;
  fit.width = fit.depth = Median(q);
  const int frontal = static_cast<int>(
      std::count_if(c.begin(), c.end(), [&](double v) { return v >= options.elliptic_split; }));
  const int side = static_cast<int>(c.size()) - frontal;
  if (frontal < options.min_frames_each_way || side < options.min_frames_each_way) return fit;
  std::vector<double> slopes;
  for (size_t i = 0; i < c.size(); ++i) {
    if (c[i] < options.elliptic_split) continue;
    for (size_t j = 0; j < c.size(); ++j) {
      if (c[j] >= options.elliptic_split || c[i] - c[j] < options.min_pair_spread) continue;
      slopes.push_back((y[i] - y[j]) / (c[i] - c[j]));
    }
  }
  if (slopes.empty()) return fit;
  const double slope = Median(slopes);
  std::vector<double> intercepts;
  for (size_t i = 0; i < c.size(); ++i) intercepts.push_back(y[i] - slope * c[i]);
  const double intercept = Median(intercepts);
  const double lo = options.min_ratio * options.min_ratio,
               hi = options.max_ratio * options.max_ratio;
  fit.depth = std::sqrt(std::clamp(intercept, lo, hi));
  fit.width = std::sqrt(std::clamp(intercept + slope, lo, hi));
  fit.elliptic = true;
  return fit;
}

void CheckFrame(const CrossSectionFitFrame& frame) {
  REENACT_CHECK(frame.skeleton_in_sensor && frame.camera && frame.mask && frame.depth,
                "cross-section fit frame needs a skeleton, camera, mask and depth");
  frame.camera->Check();
  const ImageGray8& mask = *frame.mask;
  const ImageDepthMm& depth = *frame.depth;
  REENACT_CHECK(mask.channels == 1 && mask.width == frame.camera->width &&
                    mask.height == frame.camera->height,
                "mask must be 1-channel of the camera's size");
  REENACT_CHECK(depth.empty() || (depth.channels == 1 && depth.width == mask.width &&
                                  depth.height == mask.height),
                "depth must be empty or 1-channel of the mask's size");
}

using PartCylinders = std::array<std::optional<Cylinder>, kBodyPartCount>;

// The cylinder's axis as drawn in the image, with the scales pixel assignment measures in.
std::optional<ProjectedPartAxis> ProjectCylinderAxis(const Cylinder& c,
                                                     const PinholeCamera& camera) {
  std::optional<ProjectedPartAxis> axis = ProjectPartAxis(c.a, c.b, camera);
  if (!axis) return axis;
  const double f_across = std::hypot(axis->normal.x() * camera.fx, axis->normal.y() * camera.fy);
  axis->distance_unit_a = std::max(c.radius * f_across / c.a.z(), 0.5);
  axis->distance_unit_b = std::max(c.radius * f_across / c.b.z(), 0.5);
  axis->end_band_a_px = EndRimBand(camera, c.a, c.b, c.radius, -axis->dir);
  axis->end_band_b_px = EndRimBand(camera, c.b, c.a, c.radius, axis->dir);
  axis->depth_a_m = c.a.z();
  axis->depth_b_m = c.b.z();
  axis->radius_m = c.radius;
  return axis;
}

// Ring k's slice of a part; not usable where a projection fails or the axis is too
// foreshortened (f_mean: the camera's mean focal length).
RingSlice SliceRing(int k, const Cylinder& c, const Eigen::Vector3d& u,
                    const ProjectedPartAxis& axis, const PinholeCamera& camera, double f_mean,
                    const CrossSectionFitOptions& options) {
  RingSlice slice;
  slice.t = MeasuredT(k, options);
  slice.centre = c.a + slice.t * (c.b - c.a);
  const auto centre_px = camera.Project(slice.centre);
  const auto step_px = camera.Project(slice.centre + kAxisStepM * u);
  const auto lo_px = camera.Project(c.a + (slice.t - options.half_slice) * (c.b - c.a));
  const auto hi_px = camera.Project(c.a + (slice.t + options.half_slice) * (c.b - c.a));
  if (!centre_px || !step_px || !lo_px || !hi_px) return slice;
  const double scale = (*step_px - *centre_px).norm() / kAxisStepM;
  if (!(scale >= options.min_axis_scale * f_mean / slice.centre.z())) return slice;
  slice.v_centre = AlongAxis(axis, *centre_px);
  double v_lo = AlongAxis(axis, *lo_px), v_hi = AlongAxis(axis, *hi_px);
  if (v_hi - v_lo < 3) {
    v_lo = slice.v_centre - 1.5;
    v_hi = slice.v_centre + 1.5;
  }
  slice.v_lo = v_lo;
  slice.lines = static_cast<int>(std::ceil(v_hi - v_lo));
  slice.usable = slice.lines >= 1;
  return slice;
}

// A part's geometry for measuring: its axis in 3D and, when it lies far enough in front of
// the camera, its ring slices with empty lines.
PartGeometry PartGeometryOf(const Cylinder& c, BodyPart part, const Skeleton& skeleton,
                            const ProjectedPartAxis& axis, const PinholeCamera& camera,
                            const CrossSectionFitOptions& options) {
  PartGeometry g;
  g.cylinder = c;
  g.u = (c.b - c.a) / c.Length();
  g.width_direction = PartWidthDirection(skeleton, part);
  const double near = std::max(options.max_ratio * c.radius, 1e-3);
  g.measurable = c.radius > 0 && std::min(c.a.z(), c.b.z()) > near;
  if (!g.measurable) return g;
  const double f_mean = 0.5 * (camera.fx + camera.fy);
  for (int k = 0; k < kShapeRings; ++k) {
    g.slices[k] = SliceRing(k, c, g.u, axis, camera, f_mean, options);
    g.lines[k].assign(std::max(g.slices[k].lines, 0), {});
  }
  return g;
}

// Files a counted pixel (v pixels along its part's projected axis, offset_px across) under
// the line of every ring slice it falls in.
void AddToRingLines(PartGeometry& g, double v, double offset_px, int x, int y) {
  for (int k = 0; k < kShapeRings; ++k) {
    const RingSlice& slice = g.slices[k];
    if (!slice.usable) continue;
    // (the epsilon keeps pixels that lie on a bin boundary up to rounding in one bin)
    const double line = std::floor(v - slice.v_lo + 1e-6);
    if (line < 0 || line >= slice.lines) continue;
    g.lines[k][static_cast<size_t>(line)].push_back({offset_px, x, y});
  }
}

// Assignment pass: labels, and each counted pixel's place along and across its axis (into
// the parts' ring lines).
Image<int8_t> AssignPixels(const ImageGray8& mask, const ImageDepthMm& depth,
                           const PartCylinders& cylinders, const ProjectedPartAxes& axes,
                           const PinholeCamera& camera, const CrossSectionFitOptions& options,
                           std::array<PartGeometry, kBodyPartCount>& parts) {
  Image<int8_t> labels(mask.width, mask.height, 1, kBackground);
  for (int y = 0; y < mask.height; ++y) {
    for (int x = 0; x < mask.width; ++x) {
      if (mask.at(x, y) < 128) continue;
      labels.at(x, y) = kNotCounted;
      const double reading =
          depth.empty() ? 0.0 : depth.at(x, y) * options.depth_scale_m;  // 0: no reading
      const auto assigned = AssignPixelToPart(Eigen::Vector2d(x, y), axes, reading);
      if (!assigned) continue;
      const int p = assigned->part;
      const Cylinder& c = *cylinders[p];
      const double z_axis = AxisDepthAt(assigned->t, c.a.z(), c.b.z());
      const ProjectedPartAxis& axis = *axes[p];
      const double f_across = std::hypot(axis.normal.x() * camera.fx, axis.normal.y() * camera.fy);
      const double cap_px = 1.1 * options.max_ratio * c.radius * f_across / z_axis + 2;
      if (std::abs(assigned->offset_px) > cap_px) continue;
      if (!depth.empty() && depth.at(x, y) != 0 &&
          std::abs(depth.at(x, y) * options.depth_scale_m - z_axis) >
              options.depth_tolerance_m + options.max_ratio * c.radius)
        continue;
      labels.at(x, y) = static_cast<int8_t>(p);
      if (parts[p].measurable)
        AddToRingLines(parts[p], assigned->t * axis.length_px, assigned->offset_px, x, y);
    }
  }
  return labels;
}

// The outer offsets (pixels across the axis, + and - side) of a ring slice's lines whose
// silhouette run ends in an edge on both sides.
struct LineEdges {
  std::vector<double> plus, minus;
};

LineEdges SilhouetteEdges(std::vector<std::vector<LinePixel>>& lines, const RingSlice& slice,
                          const ProjectedPartAxis& axis, const EdgeTest& is_edge, int part) {
  LineEdges edges;
  for (size_t line = 0; line < lines.size(); ++line) {
    const double v = slice.v_lo + line + 0.5;
    const auto run = AxisRun(lines[line], is_edge.labels, axis, v);
    if (!run) continue;
    if (!is_edge(run->second.x, run->second.y, axis.normal, part) ||
        !is_edge(run->first.x, run->first.y, -axis.normal, part))
      continue;
    edges.plus.push_back(run->second.offset + 0.5);
    edges.minus.push_back(run->first.offset - 0.5);
  }
  return edges;
}

// Ring k of a measurable part from its silhouette edges; nullopt where too few lines have
// both edges or the tangent planes degenerate.
std::optional<RingMeasurement> MeasureRing(PartGeometry& g, int k, int part,
                                           const ProjectedPartAxis& axis,
                                           const Image<int8_t>& labels, const ImageDepthMm& depth,
                                           const PinholeCamera& camera,
                                           const CrossSectionFitOptions& options) {
  const RingSlice& slice = g.slices[k];
  const EdgeTest is_edge{labels, depth, options.depth_scale_m, options.depth_tolerance_m};
  const LineEdges edges = SilhouetteEdges(g.lines[k], slice, axis, is_edge, part);
  if (static_cast<int>(edges.plus.size()) < options.min_lines) return std::nullopt;
  const Eigen::Vector2d on_axis = axis.a + slice.v_centre * axis.dir;
  const Eigen::Vector2d edge_plus = on_axis + Median(edges.plus) * axis.normal;
  const Eigen::Vector2d edge_minus = on_axis + Median(edges.minus) * axis.normal;
  // The 3D direction across the axis that the image's +normal side shows.
  const double z = slice.centre.z();
  Eigen::Vector3d side = camera.Unproject(on_axis + axis.normal, z) - camera.Unproject(on_axis, z);
  side -= side.dot(g.u) * g.u;
  if (!(side.norm() > 0)) return std::nullopt;
  const auto h_plus = SupportAtEdge(camera, edge_plus, slice.centre, g.u, side);
  const auto h_minus = SupportAtEdge(camera, edge_minus, slice.centre, g.u, -side);
  if (!h_plus || !h_minus) return std::nullopt;
  const double r = g.cylinder.radius;
  const double q = (h_plus->h + h_minus->h) / (2 * r);
  if (!std::isfinite(q) || !(q > 0)) return std::nullopt;
  RingMeasurement m;
  m.t = slice.t;
  m.radius_m = r;
  m.half_width = q;
  if (g.width_direction) {
    const double cp = h_plus->normal.dot(*g.width_direction);
    const double cm = h_minus->normal.dot(*g.width_direction);
    m.width_weight = std::array<double, 2>{cp * cp, cm * cm};
  }
  return m;
}

}  // namespace

void CrossSectionFitOptions::Check() const {
  REENACT_CHECK(std::isfinite(end_inset) && end_inset > 0 && end_inset < RingT(1),
                "end_inset must be in (0, 1 / (kShapeRings - 1))");
  REENACT_CHECK(std::isfinite(half_slice) && half_slice > 0 && half_slice <= 0.5 * RingT(1),
                "half_slice must be in (0, 0.5 / (kShapeRings - 1)]");
  REENACT_CHECK(min_lines >= 1, "min_lines must be >= 1");
  REENACT_CHECK(std::isfinite(min_axis_scale) && min_axis_scale > 0 && min_axis_scale <= 1,
                "min_axis_scale must be in (0, 1]");
  REENACT_CHECK(std::isfinite(depth_tolerance_m) && depth_tolerance_m >= 0,
                "depth_tolerance_m must be finite and >= 0");
  REENACT_CHECK(std::isfinite(depth_scale_m) && depth_scale_m > 0,
                "depth_scale_m must be finite and > 0");
  REENACT_CHECK(std::isfinite(min_ratio) && min_ratio > 0 && min_ratio <= 1,
                "min_ratio must be in (0, 1]");
  REENACT_CHECK(std::isfinite(max_ratio) && max_ratio >= 1, "max_ratio must be finite and >= 1");
  REENACT_CHECK(std::isfinite(elliptic_split) && elliptic_split > 0 && elliptic_split < 1,
                "elliptic_split must be in (0, 1)");
  REENACT_CHECK(min_frames_each_way >= 1, "min_frames_each_way must be >= 1");
  REENACT_CHECK(std::isfinite(min_pair_spread) && min_pair_spread > 0 && min_pair_spread <= 1,
                "min_pair_spread must be in (0, 1]");
}

CrossSectionMeasurements MeasureCrossSections(const CrossSectionFitFrame& frame,
                                              const RadiusRatios& ratios,
                                              const PartExtensions& extensions,
                                              const CrossSectionFitOptions& options) {
  options.Check();
  CheckFrame(frame);
  const Skeleton& skeleton = *frame.skeleton_in_sensor;
  const PinholeCamera& camera = *frame.camera;
  const ImageDepthMm& depth = *frame.depth;

  const PartCylinders cylinders = PoseCylinders(skeleton, ratios, extensions);
  ProjectedPartAxes axes;
  std::array<PartGeometry, kBodyPartCount> parts;
  for (int p = 0; p < kBodyPartCount; ++p) {
    if (!cylinders[p]) continue;
    axes[p] = ProjectCylinderAxis(*cylinders[p], camera);
    if (!axes[p]) continue;
    parts[p] = PartGeometryOf(*cylinders[p], static_cast<BodyPart>(p), skeleton, *axes[p], camera,
                              options);
  }

  const Image<int8_t> labels =
      AssignPixels(*frame.mask, depth, cylinders, axes, camera, options, parts);

  CrossSectionMeasurements out{};
  for (int p = 0; p < kBodyPartCount; ++p) {
    if (!parts[p].measurable) continue;
    for (int k = 0; k < kShapeRings; ++k)
      if (parts[p].slices[k].usable)
        out[p][k] = MeasureRing(parts[p], k, p, *axes[p], labels, depth, camera, options);
  }
  return out;
}

CrossSectionFitResult FitCrossSections(std::span<const CrossSectionFitFrame> frames,
                                       const RadiusRatios& ratios, const PartExtensions& extensions,
                                       const CrossSectionFitOptions& options) {
  options.Check();
  std::array<std::array<std::vector<RingMeasurement>, kShapeRings>, kBodyPartCount> samples;
  CrossSectionFitResult result;
  for (const CrossSectionFitFrame& frame : frames) {
    const CrossSectionMeasurements m = MeasureCrossSections(frame, ratios, extensions, options);
    for (int p = 0; p < kBodyPartCount; ++p) {
      bool any = false;
      for (int k = 0; k < kShapeRings; ++k)
        if (m[p][k]) {
          samples[p][k].push_back(*m[p][k]);
          any = true;
        }
      if (any) ++result.frames_measured[p];
    }
  }
  for (int p = 0; p < kBodyPartCount; ++p) {
    if (result.frames_measured[p] == 0) continue;
    std::array<std::optional<RingFit>, kShapeRings> rings;
    std::array<std::optional<double>, kShapeRings> separated_width, separated_depth;
    for (int k = 0; k < kShapeRings; ++k) {
      if (samples[p][k].empty()) continue;
      rings[k] = FitRing(samples[p][k], options);
      if (!rings[k]->elliptic) continue;
      separated_width[k] = rings[k]->width;
      separated_depth[k] = rings[k]->depth;
    }
    result.elliptic[p] = std::any_of(separated_width.begin(), separated_width.end(),
                                     [](const auto& w) { return w.has_value(); });
    if (result.elliptic[p]) {
      const auto other_width = FillRings(separated_width, options);
      const auto other_depth = FillRings(separated_depth, options);
      for (int k = 0; k < kShapeRings; ++k) {
        if (!rings[k] || rings[k]->elliptic) continue;
        const auto ring =
            FitRingWithOtherAxis(samples[p][k], other_width[k], other_depth[k], options);
        if (ring) rings[k] = ring;
      }
    }
    std::array<std::optional<double>, kShapeRings> width, depth;
    for (int k = 0; k < kShapeRings; ++k) {
      if (!rings[k]) continue;
      width[k] = rings[k]->width;
      depth[k] = rings[k]->depth;
    }
    result.fitted[p] = true;
    result.shape[p].width = CompleteRings(width, options);
    result.shape[p].depth = CompleteRings(depth, options);
  }
  return result;
}

CrossSectionError MeasureCrossSectionError(std::span<const CrossSectionFitFrame> frames,
                                           const RadiusRatios& ratios,
                                           const PartExtensions& extensions,
                                           const PartShapes& shapes,
                                           const CrossSectionFitOptions& options) {
  options.Check();
  CrossSectionError error;
  std::array<double, kBodyPartCount> sum{};
  double sum_all = 0;
  for (const CrossSectionFitFrame& frame : frames) {
    const CrossSectionMeasurements m = MeasureCrossSections(frame, ratios, extensions, options);
    for (int p = 0; p < kBodyPartCount; ++p) {
      const PartShape& shape = shapes[p];
      std::array<double, kShapeRings> round{};
      for (int k = 0; k < kShapeRings; ++k) round[k] = std::sqrt(shape.width[k] * shape.depth[k]);
      for (int k = 0; k < kShapeRings; ++k) {
        if (!m[p][k]) continue;
        const RingMeasurement& ring = *m[p][k];
        double predicted;
        if (shape.IsCircular()) {
          predicted = RingValueAt(shape.width, ring.t);
        } else if (!ring.width_weight) {
          predicted = RingValueAt(round, ring.t);
        } else {
          const double w = RingValueAt(shape.width, ring.t), d = RingValueAt(shape.depth, ring.t);
          predicted = 0;
          for (double c : *ring.width_weight)
            predicted += 0.5 * std::sqrt(w * w * c + d * d * (1 - c));
        }
        const double e = std::abs(predicted - ring.half_width) * ring.radius_m;
        sum[p] += e;
        sum_all += e;
        ++error.samples[p];
        ++error.samples_all;
      }
    }
  }
  for (int p = 0; p < kBodyPartCount; ++p)
    if (error.samples[p] > 0) error.mean_abs_m[p] = sum[p] / error.samples[p];
  if (error.samples_all > 0) error.mean_abs_m_all = sum_all / error.samples_all;
  return error;
}

}  // namespace reenact
