#include "common/texture/subject_light.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <optional>
#include <tuple>
#include <unordered_map>
#include <utility>

#include "common/error/check.h"
#include "common/model/cylinder_model.h"

namespace reenact {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kUnitNormalTolerance = 1e-3;
constexpr double kMinPatternStep = 1e-3;
constexpr int kMaxPatternEvaluations = 1000;
// Rounds of robust reweighting after the least-squares fit.
constexpr int kRobustRounds = 2;
// The least residual scale of the reweighting, grey levels: 8-bit rounding and the JPEG coding
// of the stored colours leave about this much on exact data, so that residuals this small are
// never taken for outliers (else only the samples whose shading is constant, those facing away
// from the light, would keep their weight).
constexpr double kMinResidualSigma = 2.0;

// The samples that carry information, grouped by compacted bin id (structure of arrays, each
// bin's samples contiguous), with the per-bin sums that do not depend on L: n, sum c, sum c^2.
class LightCost {
 public:
  // bin_of[i]: the compact bin of samples[i], or -1 when the sample is not used.
  LightCost(std::span<const LightSample> samples, const std::vector<int>& bin_of, int bins)
      : begin_(bins + 1, 0),
        count_(bins, 0),
        sc_(bins, 0),
        scc_(bins, 0),
        scm_(bins, 0),
        sm_(bins, 0),
        smm_(bins, 0) {
    for (int b : bin_of)
      if (b >= 0) ++begin_[b + 1];
    for (int b = 0; b < bins; ++b) begin_[b + 1] += begin_[b];
    const size_t n = begin_[bins];
    nx_.resize(n);
    ny_.resize(n);
    nz_.resize(n);
    value_.resize(n);
    weight_.assign(n, 1.0);
    std::vector<size_t> next(begin_.begin(), begin_.end() - 1);
    for (size_t i = 0; i < samples.size(); ++i) {
      const int b = bin_of[i];
      if (b < 0) continue;
      const size_t k = next[b]++;
      nx_[k] = samples[i].normal_in_world.x();
      ny_[k] = samples[i].normal_in_world.y();
      nz_[k] = samples[i].normal_in_world.z();
      value_[k] = samples[i].value;
    }
    SumValues();
  }

  // Per-bin weighted sums of 1, c and c^2.
  void SumValues() {
    for (size_t b = 0; b < count_.size(); ++b) {
      double n = 0, sc = 0, scc = 0;
      for (size_t k = begin_[b]; k < begin_[b + 1]; ++k) {
        n += weight_[k];
        sc += weight_[k] * value_[k];
        scc += weight_[k] * value_[k] * value_[k];
      }
      count_[b] = n;
      sc_[b] = sc;
      scc_[b] = scc;
    }
  }

  // Cauchy weights w = 1 / (1 + (r / (2.385 sigma))^2) of the residuals r = c - a_b s under
  // `light` (a_b each bin's weighted least-squares albedo), sigma = 1.4826 median |r| but at
  // least kMinResidualSigma.
  void Reweight(const Eigen::Vector3d& light) {
    std::vector<double> residual(value_.size());
    for (size_t b = 0; b < count_.size(); ++b) {
      double cs = 0, ss = 0;
      for (size_t k = begin_[b]; k < begin_[b + 1]; ++k) {
        const double s = SubjectShade(Eigen::Vector3d(nx_[k], ny_[k], nz_[k]), light);
        cs += weight_[k] * value_[k] * s;
        ss += weight_[k] * s * s;
      }
      const double albedo = ss > 0 ? cs / ss : 0;
      for (size_t k = begin_[b]; k < begin_[b + 1]; ++k)
        residual[k] = std::abs(
            value_[k] - albedo * SubjectShade(Eigen::Vector3d(nx_[k], ny_[k], nz_[k]), light));
    }
    std::vector<double> sorted = residual;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double scale = 2.385 * std::max(1.4826 * sorted[sorted.size() / 2], kMinResidualSigma);
    for (size_t k = 0; k < value_.size(); ++k) {
      const double q = residual[k] / scale;
      weight_[k] = 1.0 / (1.0 + q * q);
    }
    SumValues();
  }

  // Sum over bins of sum w (c - mean c)^2: the cost of flat light.
  double FlatCost() const {
    double cost = 0;
    for (size_t b = 0; b < count_.size(); ++b) {
      const double mean = sc_[b] / count_[b];
      for (size_t k = begin_[b]; k < begin_[b + 1]; ++k) {
        const double r = value_[k] - mean;
        cost += weight_[k] * r * r;
      }
    }
    return cost;
  }

  // Per-bin sums of m = max(0, n . l), c m and m^2 for a unit direction l.
  void SetDirection(const Eigen::Vector3d& l) {
    const double lx = l.x(), ly = l.y(), lz = l.z();
    for (size_t b = 0; b < count_.size(); ++b) {
      double scm = 0, sm = 0, smm = 0;
      for (size_t k = begin_[b]; k < begin_[b + 1]; ++k) {
        const double d = nx_[k] * lx + ny_[k] * ly + nz_[k] * lz;
        const double m = 0.5 * (d + std::abs(d));  // max(0, d) without a branch, exact
        const double wm = weight_[k] * m;
        scm += value_[k] * wm;
        sm += wm;
        smm += wm * m;
      }
      scm_[b] = scm;
      sm_[b] = sm;
      smm_[b] = smm;
    }
  }

  // The cost of L = k l (l the last SetDirection), k >= 0: with s = 1 + k m per sample,
  // sum c s = sc + k scm and sum s^2 = n + 2 k sm + k^2 smm per bin.
  double Cost(double k) const {
    double cost = 0;
    for (size_t b = 0; b < count_.size(); ++b) {
      const double cs = sc_[b] + k * scm_[b];
      const double ss = count_[b] + k * (2 * sm_[b] + k * smm_[b]);
      cost += std::max(0.0, scc_[b] - cs * cs / ss);
    }
    return cost;
  }

  double CostOf(const Eigen::Vector3d& light) {
    const double k = light.norm();
    if (!(k > 0)) return Cost(0);
    SetDirection(light / k);
    return Cost(k);
  }

 private:
  std::vector<size_t> begin_;  // bin b's samples: [begin_[b], begin_[b + 1])
  std::vector<double> nx_, ny_, nz_, value_, weight_;
  std::vector<double> count_, sc_, scc_, scm_, sm_, smm_;
};

// N nearly evenly spread unit vectors (the Fibonacci sphere).
Eigen::Vector3d FibonacciDirection(int i, int n) {
  const double golden_angle = kPi * (3.0 - std::sqrt(5.0));
  const double z = 1.0 - (2.0 * i + 1.0) / n;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = golden_angle * i;
  return Eigen::Vector3d(r * std::cos(phi), r * std::sin(phi), z);
}

bool UsableSample(const LightSample& s) {
  if (s.bin < 0 || !std::isfinite(s.value) || !s.normal_in_world.allFinite()) return false;
  return std::abs(s.normal_in_world.norm() - 1.0) <= kUnitNormalTolerance;
}

// The body-fixed frame of one part's bins: axis start a, unit axis u, unit left direction r
// orthogonal to u, w = u x r, and the axis length.
struct PartBinFrame {
  Eigen::Vector3d a, u, r, w;
  double length = 0;
};

std::pair<Joint, Joint> LeftJoints(BodyPart part) {
  switch (part) {
    case BodyPart::kLowerTorso:
    case BodyPart::kLeftThigh:
    case BodyPart::kLeftShin:
    case BodyPart::kRightThigh:
    case BodyPart::kRightShin:
      return {Joint::kLeftHip, Joint::kRightHip};
    default:
      return {Joint::kLeftShoulder, Joint::kRightShoulder};
  }
}

std::optional<PartBinFrame> BinFrameOf(const Skeleton& skeleton, BodyPart part, double min_sine) {
  const auto [ja, jb] = PartJoints(part);
  const auto [jl, jr] = LeftJoints(part);
  if (!skeleton.Has(ja) || !skeleton.Has(jb) || !skeleton.Has(jl) || !skeleton.Has(jr))
    return std::nullopt;
  PartBinFrame f;
  f.a = skeleton[ja];
  const Eigen::Vector3d axis = skeleton[jb] - f.a;
  f.length = axis.norm();
  if (!(f.length >= kMinBoneLength) || !std::isfinite(f.length)) return std::nullopt;
  f.u = axis / f.length;
  const Eigen::Vector3d left = skeleton[jl] - skeleton[jr];
  const double left_length = left.norm();
  if (!(left_length > 0) || !std::isfinite(left_length)) return std::nullopt;
  const Eigen::Vector3d r = left - left.dot(f.u) * f.u;
  const double r_length = r.norm();
  if (!(r_length > 0) || !(r_length >= min_sine * left_length)) return std::nullopt;
  f.r = r / r_length;
  f.w = f.u.cross(f.r);
  return f;
}

int BinIn(const PartBinFrame& f, BodyPart part, const Eigen::Vector3d& x,
          const LightSampleBins& bins) {
  if (!x.allFinite()) return -1;
  const Eigen::Vector3d d = x - f.a;
  const double t = std::clamp(d.dot(f.u) / f.length, 0.0, 1.0);
  const int axial =
      std::min(static_cast<int>(std::floor(t * bins.axial_bins)), bins.axial_bins - 1);
  double angle = std::atan2(d.dot(f.w), d.dot(f.r));
  if (angle < 0) angle += 2 * kPi;
  const int angular =
      std::clamp(static_cast<int>(std::floor(angle / (2 * kPi) * bins.angular_bins)), 0,
                 bins.angular_bins - 1);
  return (Index(part) * bins.axial_bins + axial) * bins.angular_bins + angular;
}

// The L of least cost: coarse search over directions x strengths (and L = 0), then a pattern
// search on its three components.
std::pair<Eigen::Vector3d, double> SearchLight(LightCost& cost, double flat_cost,
                                               const SubjectLightFitOptions& options) {
  // Improvements smaller than this are rounding noise, not light.
  const double tolerance = 1e-12 * flat_cost;

  // Coarse search: L = 0 and directions x strengths.
  Eigen::Vector3d best = Eigen::Vector3d::Zero();
  double best_cost = flat_cost;
  for (int i = 0; i < options.directions; ++i) {
    const Eigen::Vector3d l = FibonacciDirection(i, options.directions);
    cost.SetDirection(l);
    for (int j = 0; j < options.strengths; ++j) {
      const double k = options.max_strength / std::ldexp(1.0, options.strengths - 1 - j);
      const double c = cost.Cost(k);
      if (c < best_cost - tolerance) {
        best_cost = c;
        best = k * l;
      }
    }
  }

  // Pattern search on the three components of L.
  double step = best.norm() > 0 ? 0.25 * best.norm() : 0.25;
  int evaluations = 0;
  while (step >= kMinPatternStep && evaluations < kMaxPatternEvaluations) {
    Eigen::Vector3d move = best;
    double move_cost = best_cost;
    for (int axis = 0; axis < 3 && evaluations < kMaxPatternEvaluations; ++axis)
      for (double sign : {1.0, -1.0}) {
        if (evaluations >= kMaxPatternEvaluations) break;
        Eigen::Vector3d candidate = best;
        candidate[axis] += sign * step;
        const double c = cost.CostOf(candidate);
        ++evaluations;
        if (c < move_cost - tolerance) {
          move_cost = c;
          move = candidate;
        }
      }
    if (move_cost < best_cost) {
      best = move;
      best_cost = move_cost;
    } else {
      step *= 0.5;
    }
  }

  return {best, best_cost};
}

// "12.3%".
std::string Percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f%%", 100 * fraction);
  return text;
}

}  // namespace

void SubjectLightFitOptions::Check() const {
  REENACT_CHECK(directions >= 8, "SubjectLightFitOptions: directions must be >= 8");
  REENACT_CHECK(strengths >= 1, "SubjectLightFitOptions: strengths must be >= 1");
  REENACT_CHECK(std::isfinite(max_strength) && max_strength > 0,
                "SubjectLightFitOptions: max_strength must be finite and > 0");
  REENACT_CHECK(min_gain >= 0 && min_gain < 1,
                "SubjectLightFitOptions: min_gain must be in [0, 1)");
  REENACT_CHECK(min_samples >= 1, "SubjectLightFitOptions: min_samples must be >= 1");
  REENACT_CHECK(min_bins >= 1, "SubjectLightFitOptions: min_bins must be >= 1");
}

SubjectLightFit FitSubjectLight(std::span<const LightSample> samples,
                                const SubjectLightFitOptions& options) {
  options.Check();
  SubjectLightFit fit;

  // Occurrences per bin among usable samples; bins seen at least twice get a compact id.
  std::unordered_map<int, int> seen;
  for (const LightSample& s : samples) {
    if (!UsableSample(s)) continue;
    ++fit.samples;
    ++seen[s.bin];
  }
  std::unordered_map<int, int> compact;
  for (const auto& [bin, count] : seen)
    if (count >= 2) compact.emplace(bin, 0);
  fit.bins = static_cast<int>(compact.size());

  if (fit.samples < options.min_samples) {
    fit.reason = "only " + std::to_string(fit.samples) +
                 " usable colour samples of the subject (at least " +
                 std::to_string(options.min_samples) +
                 " needed) to measure the light; the clip is shown without relighting";
    return fit;
  }
  if (fit.bins < options.min_bins) {
    fit.reason = "only " + std::to_string(fit.bins) +
                 " patches of the body were seen more than once (at least " +
                 std::to_string(options.min_bins) +
                 " needed) to measure the light; the clip is shown without relighting";
    return fit;
  }

  // Compact ids in increasing bin order, so the result does not depend on hashing.
  std::vector<int> ordered;
  ordered.reserve(compact.size());
  for (const auto& entry : compact) ordered.push_back(entry.first);
  std::sort(ordered.begin(), ordered.end());
  for (size_t i = 0; i < ordered.size(); ++i) compact[ordered[i]] = static_cast<int>(i);

  std::vector<int> bin_of(samples.size(), -1);
  for (size_t i = 0; i < samples.size(); ++i) {
    if (!UsableSample(samples[i])) continue;
    const auto it = compact.find(samples[i].bin);
    if (it != compact.end()) bin_of[i] = it->second;
  }
  LightCost cost(samples, bin_of, fit.bins);

  const double flat_cost = cost.FlatCost();
  if (!(flat_cost > 0) || !std::isfinite(flat_cost)) {
    fit.reason =
        "the subject's colours do not change as it turns: the light is flat (or the clip shows "
        "no shading); the clip is shown without relighting";
    return fit;
  }
  Eigen::Vector3d best = Eigen::Vector3d::Zero();
  double best_cost = flat_cost, weighted_flat_cost = flat_cost;
  for (int round = 0; round <= kRobustRounds; ++round) {
    if (round > 0) {
      cost.Reweight(best);
      const double weighted = cost.FlatCost();
      if (!(weighted > 0) || !std::isfinite(weighted)) break;  // keep the last round's fit
      weighted_flat_cost = weighted;
    }
    std::tie(best, best_cost) = SearchLight(cost, weighted_flat_cost, options);
  }
  fit.gain = std::clamp(1.0 - best_cost / weighted_flat_cost, 0.0, 1.0);
  if (!(best.norm() > 0) || fit.gain < options.min_gain || fit.gain <= 0) {
    fit.reason = "no directional light explains the subject's colours (the best light removes " +
                 Percent(fit.gain) + " of their variation, at least " + Percent(options.min_gain) +
                 " needed): the light is taken as flat and the clip is shown without relighting";
    return fit;
  }
  fit.light = best;
  fit.found = true;
  return fit;
}

void LightSampleBins::Check() const {
  REENACT_CHECK(axial_bins >= 1, "LightSampleBins: axial_bins must be >= 1");
  REENACT_CHECK(angular_bins >= 1, "LightSampleBins: angular_bins must be >= 1");
  REENACT_CHECK(static_cast<int64_t>(kBodyPartCount) * axial_bins * angular_bins <=
                    std::numeric_limits<int>::max(),
                "LightSampleBins: too many bins (kBodyPartCount * axial_bins * angular_bins "
                "must fit in an int)");
  REENACT_CHECK(min_sine >= 0 && min_sine < 1, "LightSampleBins: min_sine must be in [0, 1)");
}

int LightSampleBin(const Skeleton& skeleton_in_sensor, BodyPart part, const Eigen::Vector3d& x,
                   const LightSampleBins& bins) {
  bins.Check();
  const auto frame = BinFrameOf(skeleton_in_sensor, part, bins.min_sine);
  return frame ? BinIn(*frame, part, x, bins) : -1;
}

void LightSampleOptions::Check() const {
  REENACT_CHECK(stride >= 1, "LightSampleOptions: stride must be >= 1");
  REENACT_CHECK(normal_step >= 1, "LightSampleOptions: normal_step must be >= 1");
  REENACT_CHECK(std::isfinite(max_depth_jump_m) && max_depth_jump_m > 0,
                "LightSampleOptions: max_depth_jump_m must be finite and > 0");
  REENACT_CHECK(max_value >= 1 && max_value <= 255,
                "LightSampleOptions: max_value must be in [1, 255]");
  bins.Check();
}

namespace {

// DepthNormal's rule with the back-projection given: point(x, y, z) is pixel (x, y)
// back-projected to depth z (PinholeCamera::Unproject).
template <typename BackProject>
std::optional<Eigen::Vector3d> NormalFromDepth(const Image<float>& depth_m,
                                               const ImageLabel8& part_labels, int x, int y,
                                               const LightSampleOptions& options,
                                               const BackProject& point) {
  if (!part_labels.Contains(x, y)) return std::nullopt;
  const int label = part_labels.at(x, y);
  if (label < 1 || label > kBodyPartCount) return std::nullopt;
  const double z = depth_m.at(x, y);
  if (!(z > 0) || !std::isfinite(z)) return std::nullopt;
  const int k = options.normal_step;
  const double max_jump = options.max_depth_jump_m * k;
  // The neighbour's depth, or 0 when it cannot take part in the normal.
  const auto neighbour_depth = [&](int xn, int yn) -> double {
    if (!part_labels.Contains(xn, yn) || part_labels.at(xn, yn) != label) return 0;
    const double zn = depth_m.at(xn, yn);
    if (!(zn > 0) || !std::isfinite(zn) || !(std::abs(zn - z) <= max_jump)) return 0;
    return zn;
  };
  const double z_left = neighbour_depth(x - k, y), z_right = neighbour_depth(x + k, y);
  const double z_up = neighbour_depth(x, y - k), z_down = neighbour_depth(x, y + k);
  if (z_left == 0 || z_right == 0 || z_up == 0 || z_down == 0) return std::nullopt;
  const Eigen::Vector3d along_x = point(x + k, y, z_right) - point(x - k, y, z_left);
  const Eigen::Vector3d along_y = point(x, y + k, z_down) - point(x, y - k, z_up);
  Eigen::Vector3d normal = along_x.cross(along_y);
  const double length = normal.norm();
  if (!(length > 0) || !std::isfinite(length)) return std::nullopt;
  normal /= length;
  if (normal.dot(point(x, y, z)) > 0) normal = -normal;
  return normal;
}

}  // namespace

std::optional<Eigen::Vector3d> DepthNormal(const Image<float>& depth_m,
                                           const ImageLabel8& part_labels,
                                           const PinholeCamera& camera, int x, int y,
                                           const LightSampleOptions& options) {
  return NormalFromDepth(depth_m, part_labels, x, y, options, [&](int px, int py, double z) {
    return camera.Unproject(Eigen::Vector2d(px, py), z);
  });
}

Image<float> DepthNormalMap(const Image<float>& depth_m, const ImageLabel8& part_labels,
                            const PinholeCamera& camera, const LightSampleOptions& options) {
  options.Check();
  camera.Check();
  const auto sized = [&](const auto& image) {
    return image.channels == 1 && image.width == camera.width && image.height == camera.height;
  };
  REENACT_CHECK(sized(depth_m) && sized(part_labels),
                "DepthNormalMap: depth and part labels must be 1-channel of the camera's size");
  // Every pixel's undistorted ray once (Unproject is ray * z), not once per neighbour use.
  const int w = camera.width;
  std::vector<Eigen::Vector2d> rays(static_cast<size_t>(w) * camera.height);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < w; ++x) rays[static_cast<size_t>(y) * w + x] = camera.Undistort({x, y});
  const auto point = [&](int px, int py, double z) {
    const Eigen::Vector2d& r = rays[static_cast<size_t>(py) * w + px];
    return Eigen::Vector3d(r.x() * z, r.y() * z, z);
  };
  Image<float> normals(camera.width, camera.height, 3, 0.0f);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < w; ++x)
      if (const auto n = NormalFromDepth(depth_m, part_labels, x, y, options, point))
        for (int k = 0; k < 3; ++k) normals.at(x, y, k) = static_cast<float>((*n)[k]);
  return normals;
}

void AppendLightSamples(const LightSampleFrame& frame, const LightSampleOptions& options,
                        std::vector<LightSample>* samples) {
  options.Check();
  REENACT_CHECK(samples != nullptr, "AppendLightSamples: samples must not be null");
  REENACT_CHECK(
      frame.skeleton_in_sensor && frame.camera && frame.color && frame.part_labels && frame.depth_m,
      "AppendLightSamples: every frame pointer must be set");
  const PinholeCamera& camera = *frame.camera;
  camera.Check();
  const ImageRgb8& color = *frame.color;
  const ImageLabel8& labels = *frame.part_labels;
  const Image<float>& depth = *frame.depth_m;
  const auto sized = [&](int w, int h) { return w == camera.width && h == camera.height; };
  REENACT_CHECK(color.channels == 3 && sized(color.width, color.height),
                "AppendLightSamples: colour must be 3-channel of the camera's size");
  REENACT_CHECK(labels.channels == 1 && sized(labels.width, labels.height),
                "AppendLightSamples: part labels must be 1-channel of the camera's size");
  REENACT_CHECK(depth.channels == 1 && sized(depth.width, depth.height),
                "AppendLightSamples: depth must be 1-channel of the camera's size");
  const Eigen::Matrix3d& world_from_sensor = frame.world_from_sensor;
  REENACT_CHECK(
      world_from_sensor.allFinite() &&
          (world_from_sensor.transpose() * world_from_sensor - Eigen::Matrix3d::Identity()).norm() <
              1e-6 &&
          world_from_sensor.determinant() > 0,
      "AppendLightSamples: world_from_sensor must be a rotation");

  std::array<std::optional<PartBinFrame>, kBodyPartCount> part_frames;
  for (int p = 0; p < kBodyPartCount; ++p)
    part_frames[p] =
        BinFrameOf(*frame.skeleton_in_sensor, static_cast<BodyPart>(p), options.bins.min_sine);

  for (int y = 0; y < camera.height; y += options.stride)
    for (int x = 0; x < camera.width; x += options.stride) {
      const int label = labels.at(x, y);
      if (label < 1 || label > kBodyPartCount) continue;
      const BodyPart part = static_cast<BodyPart>(label - 1);
      if (!part_frames[label - 1]) continue;
      const int r = color.at(x, y, 0), g = color.at(x, y, 1), b = color.at(x, y, 2);
      if (r > options.max_value || g > options.max_value || b > options.max_value) continue;
      const auto normal = DepthNormal(depth, labels, camera, x, y, options);
      if (!normal) continue;
      const Eigen::Vector3d point = camera.Unproject(Eigen::Vector2d(x, y), depth.at(x, y));
      const int bin = BinIn(*part_frames[label - 1], part, point, options.bins);
      if (bin < 0) continue;
      samples->push_back({bin, world_from_sensor * *normal, (r + g + b) / 3.0});
    }
}

}  // namespace reenact
