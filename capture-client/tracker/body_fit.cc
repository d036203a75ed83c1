#include "capture-client/tracker/body_fit.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "common/error/check.h"

namespace reenact::capture {
namespace {

constexpr int kN = ArticulatedBody::kParameterCount;
using Mat = Eigen::Matrix<double, kN, kN>;
using Vec = Eigen::Matrix<double, kN, 1>;

// The share of a capsule of radius r about the segment a-b (sensor frame) that projects inside
// the camera's image: at kImageShareSamples points spread along the axis, the share of the
// square of the capsule's projected width around the point's pixel that lies in the image
// (for r = 0, whether the pixel does); 0 at points behind the sensor.
constexpr int kImageShareSamples = 8;
double ShareInImage(const PinholeCamera& camera, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                    double r) {
  const auto inside = [](double centre, double half, double size) {
    if (half <= 0) return centre >= 0 && centre < size ? 1.0 : 0.0;
    return std::clamp((std::min(centre + half, size) - std::max(centre - half, 0.0)) / (2 * half),
                      0.0, 1.0);
  };
  double sum = 0;
  for (int k = 0; k < kImageShareSamples; ++k) {
    const Eigen::Vector3d q = a + (k + 0.5) / kImageShareSamples * (b - a);
    const auto px = camera.Project(q, 0.1);
    if (!px) continue;
    const double hx = camera.fx * r / q.z(), hy = camera.fy * r / q.z();
    sum += inside(px->x(), hx, camera.width) * inside(px->y(), hy, camera.height);
  }
  return sum / kImageShareSamples;
}

// 1D squared Euclidean distance transform (Felzenszwalb and Huttenlocher 2012).
void Edt1d(const std::vector<double>& f, std::vector<double>* d, std::vector<int>* v,
           std::vector<double>* z) {
  const int n = static_cast<int>(f.size());
  v->assign(n, 0);
  z->assign(n + 1, 0);
  d->assign(n, 0);
  int k = 0;
  (*v)[0] = 0;
  (*z)[0] = -std::numeric_limits<double>::infinity();
  (*z)[1] = std::numeric_limits<double>::infinity();
  for (int q = 1; q < n; ++q) {
    double s;
    while (true) {
      const int p = (*v)[k];
      s = ((f[q] + q * q) - (f[p] + p * p)) / (2.0 * q - 2.0 * p);
      if (s <= (*z)[k] && k > 0) {
        --k;
        continue;
      }
      break;
    }
    if (s <= (*z)[k]) {  // k == 0 and the new parabola wins everywhere
      (*v)[0] = q;
      (*z)[1] = std::numeric_limits<double>::infinity();
      continue;
    }
    ++k;
    (*v)[k] = q;
    (*z)[k] = s;
    (*z)[k + 1] = std::numeric_limits<double>::infinity();
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while ((*z)[k + 1] < q) ++k;
    const int p = (*v)[k];
    (*d)[q] = (q - p) * (q - p) + f[p];
  }
}

// Distance (pixels) from every pixel to the nearest mask pixel; 0 inside; a large finite value
// everywhere when the mask is empty.
Image<float> DistanceToMask(const ImageGray8& mask) {
  const int w = mask.width, h = mask.height;
  const double inf = 1e12;
  Image<float> out(w, h, 1, 0.f);
  std::vector<double> grid(static_cast<size_t>(w) * h);
  for (size_t i = 0; i < grid.size(); ++i) grid[i] = mask.data[i] ? 0 : inf;
  std::vector<double> f, d, z;
  std::vector<int> v;
  for (int x = 0; x < w; ++x) {
    f.resize(h);
    for (int y = 0; y < h; ++y) f[y] = grid[y * w + x];
    Edt1d(f, &d, &v, &z);
    for (int y = 0; y < h; ++y) grid[y * w + x] = d[y];
  }
  for (int y = 0; y < h; ++y) {
    f.assign(grid.begin() + y * w, grid.begin() + (y + 1) * w);
    Edt1d(f, &d, &v, &z);
    for (int x = 0; x < w; ++x) out.at(x, y) = static_cast<float>(std::sqrt(std::min(d[x], 1e8)));
  }
  return out;
}

struct PosedCapsule {
  int segment;
  Eigen::Vector3d a, b;
  double radius;
  // Its bounding sphere: the axis's midpoint, half the axis's length plus the radius.
  Eigen::Vector3d centre;
  double bound;
};

// The body's capsules posed in the sensor frame.
std::vector<PosedCapsule> PoseCapsules(const ArticulatedBody& body, const PosedBody3& posed) {
  std::vector<PosedCapsule> caps;
  for (const BodyCapsule& c : body.capsules()) {
    const Eigen::Isometry3d& t = posed.sensor_from_segment[static_cast<int>(c.segment)];
    const Eigen::Vector3d a = t * c.a, b = t * c.b;
    caps.push_back({static_cast<int>(c.segment), a, b, c.radius, 0.5 * (a + b),
                    0.5 * (b - a).norm() + c.radius});
  }
  return caps;
}

// Nearest point on segment a-b to p.
Eigen::Vector3d NearestOnAxis(const PosedCapsule& c, const Eigen::Vector3d& p) {
  const Eigen::Vector3d ab = c.b - c.a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - c.a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return c.a + t * ab;
}

class Problem {
 public:
  Problem(const ArticulatedBody& body, const BodyObservation& obs, const BodyFitOptions& o)
      : body_(body), obs_(obs), o_(o) {
    for (int s = 0; s < kBodySegmentCount; ++s) {
      params_[s] = {0, 1, 2};  // the root's translation
      for (int a = s; a >= 0; a = SegmentParent(static_cast<BodySegment>(a))) {
        chain_[s].push_back(a);
        const BodySegment seg = static_cast<BodySegment>(a);
        const int k = ArticulatedBody::ParameterIndex(seg);
        for (int i = 0; i < (IsHinge(seg) ? 1 : 3); ++i) params_[s].push_back(k + i);
      }
    }
  }

  struct Evaluation {
    double cost = 0;
    Mat H = Mat::Zero();
    Vec g = Vec::Zero();
    int inliers = 0, outliers = 0, used = 0, samples = 0;
    Eigen::Vector3d inlier_sum = Eigen::Vector3d::Zero();
    double data_sq = 0, sil_sq = 0;
    std::array<int, kBodySegmentCount> support{};
  };

  Evaluation Evaluate(const PosedBody3& posed, bool jacobian) const {
    Evaluation ev;
    for (std::vector<double>& r : rows_) r.clear();
    const std::vector<PosedCapsule> caps = PoseCapsules(body_, posed);
    nearest_.resize(obs_.points.size(), -1);
    const double delta = o_.huber_m;
    for (size_t i = 0; i < obs_.points.size(); ++i) {
      const Eigen::Vector3d& p = obs_.points[i];
      // The nearest capsule (the first of equals), starting from the last evaluation's: a
      // capsule whose bounding sphere lies farther than the best residual so far is passed.
      int bi = nearest_[i];
      double best = std::numeric_limits<double>::infinity();
      Eigen::Vector3d bc;
      if (bi >= 0) bc = NearestOnAxis(caps[bi], p), best = (p - bc).norm() - caps[bi].radius;
      for (int k = 0; k < static_cast<int>(caps.size()); ++k) {
        if (k == nearest_[i]) continue;
        const double r = caps[k].bound + best;
        if ((p - caps[k].centre).squaredNorm() > r * r) continue;
        const Eigen::Vector3d c = NearestOnAxis(caps[k], p);
        const double e = (p - c).norm() - caps[k].radius;
        if (e < best || (e == best && k < bi)) best = e, bi = k, bc = c;
      }
      nearest_[i] = bi;
      if (bi < 0 || best > o_.outlier_m) {
        ++ev.outliers;
        continue;
      }
      ++ev.used;
      const double ae = std::abs(best);
      if (ae <= o_.inlier_m) ++ev.inliers, ++ev.support[caps[bi].segment], ev.inlier_sum += p;
      ev.data_sq += best * best;
      ev.cost += HuberCost(best, delta);
      if (!jacobian) continue;
      const Eigen::Vector3d d = p - bc;
      const double dn = d.norm();
      if (dn < 1e-9) continue;
      const double w = ae <= delta ? 1.0 : delta / ae;
      Accumulate(posed, caps[bi].segment, bc, -d / dn, best, w);
    }
    // Silhouette and free space.
    const int m = o_.samples_per_capsule;
    if (m > 0 && o_.silhouette_weight > 0 && !obs_.points.empty()) {
      const double w = SilhouetteSampleWeight(obs_, o_, static_cast<int>(caps.size()));
      for (const PosedCapsule& c : caps)
        for (int i = 0; i < m; ++i) {
          const double t = m == 1 ? 0.5 : static_cast<double>(i) / (m - 1);
          const Eigen::Vector3d q = c.a + t * (c.b - c.a);
          double e = 0;
          Eigen::Vector3d grad;
          if (!SilhouetteResidual(obs_, q, &e, &grad)) continue;
          ++ev.samples;
          ev.sil_sq += e * e;
          ev.cost += 0.5 * w * e * e;
          if (jacobian) Accumulate(posed, c.segment, q, grad, e, w);
        }
    }
    if (jacobian) SumRows(&ev);
    return ev;
  }

 private:
  // Adds the row of a residual e whose gradient with respect to the point x (carried by
  // segment s) is gx, weighted by w, to the segment's rows (see rows_).
  void Accumulate(const PosedBody3& posed, int s, const Eigen::Vector3d& x,
                  const Eigen::Vector3d& gx, double e, double w) const {
    const double sw = std::sqrt(w);
    std::vector<double>& r = rows_[s];
    r.insert(r.end(), {sw * gx.x(), sw * gx.y(), sw * gx.z()});
    for (int a : chain_[s]) {
      const BodySegment seg = static_cast<BodySegment>(a);
      const Eigen::Isometry3d& t = posed.sensor_from_segment[a];
      const Eigen::Vector3d moment = sw * (x - t.translation()).cross(gx);
      if (IsHinge(seg)) {
        const double sign =
            seg == BodySegment::kLeftForearm || seg == BodySegment::kRightForearm ? -1.0 : 1.0;
        r.push_back(sign * t.linear().col(1).dot(moment));
      } else {
        r.insert(r.end(), {moment.x(), moment.y(), moment.z()});
      }
    }
    r.push_back(sw * e);
  }

  // H = sum of w J^T J and g = sum of w J^T e over the rows, one product per segment over its
  // chain's parameters, scattered into the full parameter vector.
  void SumRows(Evaluation* ev) const {
    for (int s = 0; s < kBodySegmentCount; ++s) {
      const std::vector<int>& k = params_[s];
      const int n = static_cast<int>(k.size());
      const int m = static_cast<int>(rows_[s].size()) / (n + 1);
      if (m == 0) continue;
      const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>
          a(rows_[s].data(), m, n + 1);
      Eigen::MatrixXd ata = Eigen::MatrixXd::Zero(n + 1, n + 1);
      ata.selfadjointView<Eigen::Lower>().rankUpdate(a.transpose());
      for (int i = 0; i < n; ++i) {
        ev->g[k[i]] += ata(n, i);
        for (int j = 0; j <= i; ++j) {
          ev->H(k[i], k[j]) += ata(i, j);
          if (i != j) ev->H(k[j], k[i]) += ata(i, j);
        }
      }
    }
  }

  const ArticulatedBody& body_;
  const BodyObservation& obs_;
  const BodyFitOptions& o_;
  std::array<std::vector<int>, kBodySegmentCount> chain_;
  // Per segment: the parameters its points depend on (the root's translation, then each
  // segment of its chain, as ParameterIndex numbers them), and the weighted Jacobian rows of
  // the residuals it carries, each params_[s].size() + 1 wide (sqrt(w) J, then sqrt(w) e).
  std::array<std::vector<int>, kBodySegmentCount> params_;
  mutable std::array<std::vector<double>, kBodySegmentCount> rows_;
  // Per data point, its nearest capsule at the last evaluation (-1 before the first).
  mutable std::vector<int> nearest_;
};

}  // namespace

bool SilhouetteResidual(const BodyObservation& obs, const Eigen::Vector3d& q, double* e,
                        Eigen::Vector3d* grad) {
  if (q.z() < 0.1) return false;
  const PinholeCamera& cam = obs.camera;
  const int gs = obs.grid_step_px;
  const double u = cam.fx * q.x() / q.z() + cam.cx, v = cam.fy * q.y() / q.z() + cam.cy;
  const int gx = static_cast<int>(std::lround(u / gs)), gy = static_cast<int>(std::lround(v / gs));
  if (gx < 1 || gy < 1 || gx >= obs.silhouette.width - 1 || gy >= obs.silhouette.height - 1)
    return false;
  if (!obs.silhouette.at(gx, gy)) {
    const Image<float>& d = obs.outside_px;
    *e = d.at(gx, gy) * gs * q.z() / cam.fx;
    const double dx = 0.5 * (d.at(gx + 1, gy) - d.at(gx - 1, gy));
    const double dy = 0.5 * (d.at(gx, gy + 1) - d.at(gx, gy - 1)) * cam.fy / cam.fx;
    *grad = Eigen::Vector3d(dx, dy, -(dx * q.x() + dy * q.y()) / q.z());
    return true;
  }
  const double zo = obs.depth_m.at(gx, gy);
  if (zo <= 0 || q.z() >= zo) return false;
  *e = zo - q.z();
  *grad = Eigen::Vector3d(0, 0, -1);
  return true;
}

double SilhouetteSampleWeight(const BodyObservation& obs, const BodyFitOptions& o,
                              int capsule_count) {
  if (o.samples_per_capsule <= 0 || capsule_count <= 0) return 0;
  return o.silhouette_weight * static_cast<double>(obs.points.size()) /
         (static_cast<double>(capsule_count) * o.samples_per_capsule);
}

void BodyFitOptions::Check() const {
  REENACT_CHECK(iterations >= 1, "iterations must be >= 1");
  REENACT_CHECK(huber_m > 0 && outlier_m > 0 && inlier_m > 0, "huber_m, outlier_m, inlier_m > 0");
  REENACT_CHECK(samples_per_capsule >= 0, "samples_per_capsule must be >= 0");
  REENACT_CHECK(silhouette_weight >= 0 && damping >= 0, "weights must be >= 0");
  REENACT_CHECK(initial_lambda > 0, "initial_lambda must be > 0");
}

BodyObservation MakeObservation(const PinholeCamera& camera, int grid_step_px,
                                const ImageGray8& silhouette, const Image<float>& depth_m,
                                const std::vector<Eigen::Vector3d>& points,
                                const std::vector<Eigen::Vector2i>& pixels, int subsample) {
  REENACT_CHECK(grid_step_px >= 1 && subsample >= 1, "grid step and subsample must be >= 1");
  REENACT_CHECK(points.size() == pixels.size(), "points and pixels differ in number");
  BodyObservation obs;
  obs.camera = camera;
  obs.grid_step_px = grid_step_px;
  obs.silhouette = silhouette;
  obs.depth_m = depth_m;
  obs.outside_px = DistanceToMask(silhouette);
  obs.point_spacing_px = grid_step_px * subsample;
  for (size_t i = 0; i < points.size(); ++i)
    if (pixels[i].x() % subsample == 0 && pixels[i].y() % subsample == 0)
      obs.points.push_back(points[i]);
  return obs;
}

int KeepPointsNearBody(const ArticulatedBody& body, const PosedBody3& posed, double max_m,
                       BodyObservation* obs) {
  const std::vector<PosedCapsule> caps = PoseCapsules(body, posed);
  const size_t before = obs->points.size();
  std::erase_if(obs->points, [&](const Eigen::Vector3d& p) {
    for (const PosedCapsule& c : caps)
      if ((p - NearestOnAxis(c, p)).norm() - c.radius <= max_m) return false;
    return true;
  });
  return static_cast<int>(before - obs->points.size());
}

SegmentSupport SupportAt(const ArticulatedBody& body, const PosedBody3& posed,
                         const BodyObservation& obs, double inlier_m) {
  std::array<int, kBodySegmentCount> partner;
  partner.fill(-1);
  for (int l = 0; l < kLimbCount; ++l) {
    const int upper = static_cast<int>(LimbUpper(static_cast<Limb>(l)));
    const int lower = static_cast<int>(LimbLower(static_cast<Limb>(l)));
    partner[upper] = lower, partner[lower] = upper;
  }
  const std::vector<PosedCapsule> caps = PoseCapsules(body, posed);
  SegmentSupport out;
  for (const Eigen::Vector3d& p : obs.points) {
    int owner = -1;
    double best = std::numeric_limits<double>::infinity();
    std::array<bool, kBodySegmentCount> within{};
    for (const PosedCapsule& c : caps) {
      const double r = c.bound + std::max(inlier_m, best);
      if ((p - c.centre).squaredNorm() > r * r) continue;
      const double e = (p - NearestOnAxis(c, p)).norm() - c.radius;
      if (std::abs(e) <= inlier_m) within[c.segment] = true;
      if (e < best) best = e, owner = c.segment;
    }
    if (owner < 0 || std::abs(best) > inlier_m) continue;
    ++out.support[owner];
    bool exclusive = true;
    if (partner[owner] >= 0)
      for (int k = 0; k < kBodySegmentCount; ++k)
        if (within[k] && k != owner && k != partner[owner]) exclusive = false;
    out.exclusive[owner] += exclusive;
  }
  return out;
}

std::vector<int> NearestSegments(const ArticulatedBody& body, const PosedBody3& posed,
                                 const std::vector<Eigen::Vector3d>& points, double max_m) {
  const std::vector<PosedCapsule> caps = PoseCapsules(body, posed);
  std::vector<int> out(points.size(), -1);
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d& p = points[i];
    double best = std::numeric_limits<double>::infinity();
    int owner = -1;
    for (const PosedCapsule& c : caps) {
      if (owner >= 0 && (p - c.centre).norm() - c.bound > best) continue;
      const double e = (p - NearestOnAxis(c, p)).norm() - c.radius;
      if (e < best) best = e, owner = c.segment;
    }
    if (std::abs(best) <= max_m) out[i] = owner;
  }
  return out;
}

double CostWithLostPoints(const BodyFitResult& fit, const BodyFitOptions& options) {
  return fit.cost + fit.outlier_share * fit.points * HuberCost(options.outlier_m, options.huber_m);
}

BodyFitResult FitBody(const ArticulatedBody& body, const ArticulatedPose& start,
                      const BodyObservation& obs, const BodyFitOptions& options,
                      const JointLimits& limits) {
  options.Check();
  BodyFitResult result;
  result.pose = start;
  ArticulatedBody::Clamp(&result.pose, limits);
  result.posed = body.Pose(result.pose);
  result.points = static_cast<int>(obs.points.size());
  result.inlier_centroid = result.pose.root_translation;
  if (obs.points.empty()) return result;

  const Problem problem(body, obs, options);
  Problem::Evaluation ev = problem.Evaluate(result.posed, true);
  double lambda = options.initial_lambda;
  const double mu = options.damping * static_cast<double>(obs.points.size());
  for (int it = 0; it < options.iterations; ++it) {
    ++result.iterations;
    Mat a = ev.H;
    a.diagonal() += lambda * ev.H.diagonal() + Vec::Constant(mu);
    const Vec step = a.ldlt().solve(-ev.g);
    if (!step.allFinite()) break;
    const ArticulatedPose next = body.Step(result.pose, result.posed, step, limits);
    const PosedBody3 posed = body.Pose(next);
    Problem::Evaluation nev = problem.Evaluate(posed, true);
    if (nev.cost < ev.cost) {
      result.pose = next;
      result.posed = posed;
      ev = std::move(nev);
      lambda = std::max(lambda / 3, 1e-7);
      if (step.norm() < 1e-6) break;
    } else {
      lambda *= 4;
      if (lambda > 1e6) break;
    }
  }
  const Problem::Evaluation final_ev = ev;
  result.cost = final_ev.cost;
  result.inlier_share = static_cast<double>(final_ev.inliers) / obs.points.size();
  result.outlier_share = static_cast<double>(final_ev.outliers) / obs.points.size();
  result.rms_m = final_ev.used > 0 ? std::sqrt(final_ev.data_sq / final_ev.used) : 0;
  result.silhouette_rms_m =
      final_ev.samples > 0 ? std::sqrt(final_ev.sil_sq / final_ev.samples) : 0;
  result.support = final_ev.support;
  if (final_ev.inliers > 0) result.inlier_centroid = final_ev.inlier_sum / final_ev.inliers;
  const PinholeCamera& cam = obs.camera;
  const double spacing = obs.point_spacing_px;
  double expected_in_image = 0;
  for (const BodyCapsule& c : body.capsules()) {
    const Eigen::Isometry3d& t = result.posed.sensor_from_segment[static_cast<int>(c.segment)];
    const Eigen::Vector3d a = t * c.a, b = t * c.b, mid = 0.5 * (a + b);
    if (mid.z() < 0.1) continue;
    const Eigen::Vector3d ray = mid.normalized();
    const Eigen::Vector3d ab = b - a;
    const double across = (ab - ab.dot(ray) * ray).norm();
    const double area = 2 * c.radius * across + std::numbers::pi * c.radius * c.radius;
    const double pixels = area * cam.fx * cam.fy / (mid.z() * mid.z()) / (spacing * spacing);
    result.expected_support[static_cast<int>(c.segment)] += pixels;
    expected_in_image += ShareInImage(cam, a, b, c.radius) * pixels;
  }
  double support = 0;
  for (int k = 0; k < kBodySegmentCount; ++k) support += result.support[k];
  result.coverage = expected_in_image > 0 ? std::min(1.0, support / expected_in_image) : 0.0;
  return result;
}

}  // namespace reenact::capture
