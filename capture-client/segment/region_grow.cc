#include "capture-client/segment/region_grow.h"

#include <algorithm>
#include <cmath>

namespace reenact::capture {

BodyPixelTest::BodyPixelTest(const ImageDepthMm& depth, double depth_scale_m, const PixelRays& rays,
                             const BodyBound& bound, const std::optional<Plane3>& floor_in_sensor,
                             const PersonSegmentOptions& options)
    : depth_(depth),
      scale_(depth_scale_m),
      min_z_(std::max(options.min_depth_m, 1e-9)),
      max_z_(options.max_depth_m),
      rays_(rays),
      bound_(bound),
      floor_(floor_in_sensor),
      options_(options) {}

bool BodyPixelTest::BodyCandidate(int x, int y, double z) const {
  if (z <= 0 || !bound_.rect().Contains(x, y)) return false;
  const Eigen::Vector3d p = rays_.Point(x, y, z);
  if (floor_ && OnOrUnderFloor(*floor_, p, options_.floor_clearance)) return false;
  return bound_.Contains(p);
}

bool BodyPixelTest::OnFloor(int x, int y, double z) const {
  return z > 0 && floor_ && OnOrUnderFloor(*floor_, rays_.Point(x, y, z), options_.floor_clearance);
}

bool BodyPixelTest::InCore(int x, int y, double z) const {
  const double r = options_.core_radius_m;
  return r > 0 && bound_.NearBone(rays_.Point(x, y, z), r * r);
}

SeedResult BoneSeeds(const BodyPixelTest& test, const PinholeCamera& camera) {
  const PersonSegmentOptions& o = test.options();
  SeedResult out;
  std::vector<uint8_t> taken;
  for (const BoneSegment& bone : test.bound().bones()) {
    Eigen::Vector3d a = bone.a, b = bone.b;
    if (a.z() <= BodyBound::kNearM && b.z() <= BodyBound::kNearM) continue;
    if (a.z() < BodyBound::kNearM || b.z() < BodyBound::kNearM) {  // clip to the near plane
      const double t = (BodyBound::kNearM - a.z()) / (b.z() - a.z());
      (a.z() < BodyBound::kNearM ? a : b) = a + t * (b - a);
    }
    const auto pa = camera.Project(a), pb = camera.Project(b);
    if (!pa || !pb) continue;
    const int n =
        1 + static_cast<int>(std::ceil(std::min((*pb - *pa).norm(), 1e5) / o.seed_step_px));
    for (int i = 0; i <= n; ++i) {
      const Eigen::Vector3d p = a + (b - a) * (static_cast<double>(i) / n);
      const auto uv = camera.Project(p);
      if (!uv) continue;
      const int x = static_cast<int>(std::lround(uv->x())),
                y = static_cast<int>(std::lround(uv->y()));
      if (x < 0 || y < 0 || x >= camera.width || y >= camera.height) continue;
      ++out.samples_in_image;
      const double z = test.Depth(x, y);
      const double noise = o.depth_step.At(p.z());
      if (z < p.z() - o.seed_in_front_m - noise || z > p.z() + o.seed_behind_m + noise) continue;
      if (!test.BodyCandidate(x, y, z)) continue;
      if (taken.empty()) taken.assign(static_cast<size_t>(camera.width) * camera.height, 0);
      const int index = y * camera.width + x;
      if (taken[index]) continue;
      taken[index] = 1;
      out.pixels.push_back(index);
    }
  }
  return out;
}

int GrowRegion(const BodyPixelTest& test, const std::vector<int>& seeds, ImageGray8* mask,
               PixelRect* box, std::vector<uint8_t>* state) {
  enum : uint8_t { kUnknown = 0, kCandidate, kRejected, kIn };
  const int w = mask->width, h = mask->height;
  state->assign(static_cast<size_t>(w) * h, kUnknown);
  std::vector<int> queue;
  queue.reserve(4096);
  for (int s : seeds) {
    if ((*state)[s] == kIn) continue;
    (*state)[s] = kIn;
    queue.push_back(s);
  }
  const DepthTolerance& step = test.options().depth_step;
  for (size_t head = 0; head < queue.size(); ++head) {
    const int index = queue[head];
    const int x = index % w, y = index / w;
    const double z = test.Depth(x, y);
    const double max_step = step.At(z);
    const int nx[4] = {x - 1, x + 1, x, x};
    const int ny[4] = {y, y, y - 1, y + 1};
    for (int k = 0; k < 4; ++k) {
      if (nx[k] < 0 || ny[k] < 0 || nx[k] >= w || ny[k] >= h) continue;
      const int n = ny[k] * w + nx[k];
      uint8_t& s = (*state)[n];
      if (s == kIn || s == kRejected) continue;
      const double zn = test.Depth(nx[k], ny[k]);
      if (s == kUnknown) {
        s = test.BodyCandidate(nx[k], ny[k], zn) ? kCandidate : kRejected;
        if (s == kRejected) continue;
      }
      if (std::abs(zn - z) > max_step && !test.InCore(nx[k], ny[k], zn)) continue;
      s = kIn;
      queue.push_back(n);
    }
  }
  *box = {w, h, 0, 0};
  for (int index : queue) {
    mask->data[index] = 255;
    const int x = index % w, y = index / w;
    box->x0 = std::min(box->x0, x), box->x1 = std::max(box->x1, x + 1);
    box->y0 = std::min(box->y0, y), box->y1 = std::max(box->y1, y + 1);
  }
  return static_cast<int>(queue.size());
}

}  // namespace reenact::capture
