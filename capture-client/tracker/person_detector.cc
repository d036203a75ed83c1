#include "capture-client/tracker/person_detector.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "common/error/check.h"

namespace reenact::capture {

void PersonDetectOptions::Check() const {
  REENACT_CHECK(grid_step_px >= 1, "grid_step_px must be >= 1");
  REENACT_CHECK(min_depth_m >= 0 && min_depth_m < max_depth_m,
                "need 0 <= min_depth_m < max_depth_m");
  REENACT_CHECK(floor_below_sensor_m >= 0, "floor_below_sensor_m must be >= 0");
  REENACT_CHECK(max_height_m > 0, "max_height_m must be > 0");
  REENACT_CHECK(min_top_m >= 0 && min_top_m < max_height_m, "need 0 <= min_top_m < max_height_m");
  REENACT_CHECK(max_bottom_m >= 0, "max_bottom_m must be >= 0");
  REENACT_CHECK(max_extent_m > 0, "max_extent_m must be > 0");
  REENACT_CHECK(min_area_m2 >= 0 && min_area_m2 < max_area_m2,
                "need 0 <= min_area_m2 < max_area_m2");
  REENACT_CHECK(max_top_width_m > 0, "max_top_width_m must be > 0");
  REENACT_CHECK(max_jump_m > 0, "max_jump_m must be > 0");
  REENACT_CHECK(assumed_stature_m > 0, "assumed_stature_m must be > 0");
  REENACT_CHECK(min_region_pixels >= 1, "min_region_pixels must be >= 1");
  REENACT_CHECK(merge_step_m >= 0 && tracking_merge_step_m >= 0,
                "merge_step_m and tracking_merge_step_m must be >= 0");
  segment.Check();
}

std::string_view DetectStatusName(DetectStatus status) {
  switch (status) {
    case DetectStatus::kOk:
      return "ok";
    case DetectStatus::kNoDepth:
      return "no_depth";
    case DetectStatus::kNoPerson:
      return "no_person";
  }
  return "unknown";
}

std::string_view FloorSourceName(FloorSource source) {
  switch (source) {
    case FloorSource::kSeen:
      return "seen";
    case FloorSource::kPersonLowest:
      return "person_lowest";
    case FloorSource::kAssumedStature:
      return "assumed_stature";
  }
  return "unknown";
}

PersonDetector::PersonDetector(const PinholeCamera& camera, double depth_scale_m,
                               const PersonDetectOptions& options)
    : camera_(camera), rays_(camera), depth_scale_m_(depth_scale_m), options_(options) {
  REENACT_CHECK(camera.width > 0 && camera.height > 0 && camera.fx > 0 && camera.fy > 0,
                "invalid camera");
  REENACT_CHECK(depth_scale_m > 0 && std::isfinite(depth_scale_m), "depth_scale_m must be > 0");
  options.Check();
}

std::optional<Plane3> PersonDetector::UpdateFloor(
    const ImageDepthMm& depth, const Eigen::Vector3d& up,
    const std::optional<Eigen::Isometry3d>& world_from_sensor, bool* refitted) {
  *refitted = false;
  const PersonSegmentOptions& so = options_.segment;
  std::vector<Eigen::Vector3d> candidates;
  const int stride = so.floor_sample_stride_px;
  for (int y = 0; y < depth.height; y += stride)
    for (int x = 0; x < depth.width; x += stride) {
      const double z = depth.at(x, y) * depth_scale_m_;
      if (z < options_.min_depth_m || z > options_.max_depth_m) continue;
      const Eigen::Vector3d p = rays_.Point(x, y, z);
      if (up.dot(p) <= -options_.floor_below_sensor_m) candidates.push_back(p);
    }
  if (floor_) {
    const Plane3 plane = floor_->in_world && world_from_sensor
                             ? floor_->plane.Transformed(world_from_sensor->inverse())
                             : floor_->plane;
    if (floor_->in_world == world_from_sensor.has_value()) {
      const FloorFit score = ScoreFloorPlane(plane, candidates, so);
      if (score.inlier_ratio >= so.floor_keep_ratio * floor_->inlier_ratio) return plane;
    }
  }
  const auto fit = FitFloorPlane(candidates, up, so);
  if (!fit) {
    floor_.reset();
    return std::nullopt;
  }
  *refitted = true;
  CachedFloor cached;
  cached.in_world = world_from_sensor.has_value();
  cached.plane = cached.in_world ? fit->plane.Transformed(*world_from_sensor) : fit->plane;
  cached.inlier_ratio = fit->inlier_ratio;
  floor_ = cached;
  return fit->plane;
}

PersonBlob PersonDetector::Detect(const ImageDepthMm& depth,
                                  const std::optional<Eigen::Isometry3d>& world_from_sensor,
                                  const std::optional<Eigen::Vector3d>& world_up,
                                  const std::optional<Eigen::Vector3d>& previous_centroid) {
  REENACT_CHECK(
      depth.width == camera_.width && depth.height == camera_.height && depth.channels == 1,
      "depth image does not match the camera");
  PersonBlob blob;
  if (!ReadDepthGrid(depth, &blob)) return blob;
  Eigen::Vector3d up = -Eigen::Vector3d::UnitY();
  if (world_from_sensor && world_up && world_up->allFinite() && world_up->norm() > 0)
    up = (world_from_sensor->linear().transpose() * *world_up).normalized();
  blob.floor_in_sensor = UpdateFloor(depth, up, world_from_sensor, &blob.floor_refitted);
  const bool floor_seen = blob.floor_in_sensor.has_value();
  // Without a floor, heights are measured from a plane below every reading in range until the
  // person's own floor is set.
  const Plane3 floor =
      floor_seen ? *blob.floor_in_sensor : Plane3{up, -(options_.max_depth_m + 1)};
  GridPoints grid = MarkCandidates(blob, floor, floor_seen);
  std::vector<Region> regions = GrowRegions(grid);
  const std::vector<int> roots = MergeRegions(
      grid, previous_centroid ? options_.tracking_merge_step_m : options_.merge_step_m, &regions);
  const int best = ChooseRegion(grid, regions, roots, previous_centroid, floor_seen, &blob);
  if (best < 0) {
    blob.status = DetectStatus::kNoPerson;
    return blob;
  }
  if (!floor_seen)
    blob.floor_in_sensor =
        PersonFloor(grid, best, up, world_from_sensor, &regions[best], &blob.floor_source);
  FillBlob(grid, regions[best], best, &blob);
  return blob;
}

Plane3 PersonDetector::PersonFloor(const GridPoints& grid, int id, const Eigen::Vector3d& up,
                                   const std::optional<Eigen::Isometry3d>& world_from_sensor,
                                   Region* r, FloorSource* source) {
  if (person_floor_ && person_floor_->in_world != world_from_sensor.has_value())
    person_floor_.reset();
  std::optional<Plane3> known;
  if (person_floor_)
    known = person_floor_->in_world ? person_floor_->plane.Transformed(world_from_sensor->inverse())
                                    : person_floor_->plane;
  // The region's lowest point along up.
  Eigen::Vector3d lowest = Eigen::Vector3d::Zero();
  double lowest_up = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < label_.size(); ++i)
    if (label_[i] == id && up.dot(grid.point[i]) < lowest_up)
      lowest_up = up.dot(grid.point[i]), lowest = grid.point[i];
  Plane3 floor;
  *source = FloorSource::kPersonLowest;
  if (!r->touches_bottom && (!known || known->SignedDistance(lowest) < 0)) {
    floor = Plane3{up, lowest_up};
    person_floor_ = CachedFloor{world_from_sensor ? floor.Transformed(*world_from_sensor) : floor,
                                world_from_sensor.has_value(), 1};
  } else if (known) {
    floor = *known;
  } else {
    *source = FloorSource::kAssumedStature;
    floor = Plane3{up, grid.floor.offset + r->top - options_.assumed_stature_m};
  }
  const double shift = floor.offset - grid.floor.offset;
  r->top -= shift;
  r->bottom -= shift;
  return floor;
}

bool PersonDetector::ReadDepthGrid(const ImageDepthMm& depth, PersonBlob* blob) const {
  const int g = options_.grid_step_px;
  const int gw = (depth.width + g - 1) / g, gh = (depth.height + g - 1) / g;
  blob->grid_step_px = g;
  blob->mask = ImageGray8(gw, gh, 1, 0);
  blob->depth_m = Image<float>(gw, gh, 1, 0.f);
  bool any = false;
  for (int y = 0; y < gh; ++y)
    for (int x = 0; x < gw; ++x) {
      const double z = depth.at(x * g, y * g) * depth_scale_m_;
      if (z >= options_.min_depth_m && z <= options_.max_depth_m && std::isfinite(z)) {
        blob->depth_m.at(x, y) = static_cast<float>(z);
        any = true;
      }
    }
  return any;
}

PersonDetector::GridPoints PersonDetector::MarkCandidates(const PersonBlob& blob,
                                                          const Plane3& floor, bool floor_seen) {
  const PersonSegmentOptions& so = options_.segment;
  GridPoints grid;
  grid.width = blob.depth_m.width;
  grid.height = blob.depth_m.height;
  grid.floor = floor;
  grid.e1 = floor.normal.unitOrthogonal();
  grid.e2 = floor.normal.cross(grid.e1);
  const int g = blob.grid_step_px, gw = grid.width, n = gw * grid.height;
  grid.point.resize(n);
  grid.height_m.assign(n, 0);
  label_.assign(n, -1);  // -1: not a candidate, -2: candidate unlabelled, >= 0: region
  for (int y = 0; y < grid.height; ++y)
    for (int x = 0; x < gw; ++x) {
      const double z = blob.depth_m.at(x, y);
      if (z <= 0) continue;
      const int i = y * gw + x;
      grid.point[i] = rays_.Point(x * g, y * g, z);
      grid.height_m[i] = floor.SignedDistance(grid.point[i]);
      if (floor_seen && (OnOrUnderFloor(floor, grid.point[i], so.floor_clearance) ||
                         grid.height_m[i] > options_.max_height_m))
        continue;
      label_[i] = -2;
    }
  return grid;
}

std::vector<PersonDetector::Region> PersonDetector::GrowRegions(const GridPoints& grid) {
  const int gw = grid.width, gh = grid.height, n = gw * gh;
  const double slope = options_.grid_step_px / camera_.fx;
  std::vector<Region> regions;
  for (int start = 0; start < n; ++start) {
    if (label_[start] != -2) continue;
    const int id = static_cast<int>(regions.size());
    Region r;
    queue_.assign(1, start);
    label_[start] = id;
    for (size_t q = 0; q < queue_.size(); ++q) {
      const int i = queue_[q];
      const int x = i % gw, y = i / gw;
      const double z = grid.point[i].z();
      ++r.pixels;
      r.sum += grid.point[i];
      r.top = std::max(r.top, grid.height_m[i]);
      r.bottom = std::min(r.bottom, grid.height_m[i]);
      const double a = grid.point[i].dot(grid.e1), b = grid.point[i].dot(grid.e2);
      r.min1 = std::min(r.min1, a), r.max1 = std::max(r.max1, a);
      r.min2 = std::min(r.min2, b), r.max2 = std::max(r.max2, b);
      r.area += (slope * z) * (slope * z);
      r.touches_bottom |= y >= gh - 2;
      const double tol = options_.segment.depth_step.At(z) + slope * z;
      const int nx[4] = {x - 1, x + 1, x, x};
      const int ny[4] = {y, y, y - 1, y + 1};
      for (int k = 0; k < 4; ++k) {
        if (nx[k] < 0 || ny[k] < 0 || nx[k] >= gw || ny[k] >= gh) continue;
        const int j = ny[k] * gw + nx[k];
        if (label_[j] != -2 || std::abs(grid.point[j].z() - z) > tol) continue;
        label_[j] = id;
        queue_.push_back(j);
      }
    }
    regions.push_back(r);
  }
  return regions;
}

std::vector<PersonDetector::Contact> PersonDetector::RegionContacts(const GridPoints& grid,
                                                                    double merge_step) const {
  const int gw = grid.width, gh = grid.height;
  std::unordered_map<uint64_t, double> gaps;
  for (int y = 0; y < gh; ++y)
    for (int x = 0; x < gw; ++x) {
      const int i = y * gw + x;
      if (label_[i] < 0) continue;
      for (const int j : {x + 1 < gw ? i + 1 : -1, y + 1 < gh ? i + gw : -1}) {
        if (j < 0 || label_[j] < 0 || label_[j] == label_[i]) continue;
        const double gap = std::abs(grid.point[i].z() - grid.point[j].z());
        if (gap > merge_step) continue;
        const uint64_t a = std::min(label_[i], label_[j]), b = std::max(label_[i], label_[j]);
        auto [it, inserted] = gaps.emplace((a << 32) | b, gap);
        if (!inserted) it->second = std::min(it->second, gap);
      }
    }
  std::vector<Contact> contacts;
  for (const auto& [key, gap] : gaps)
    contacts.push_back({gap, static_cast<int>(key >> 32), static_cast<int>(key & 0xffffffffu)});
  std::sort(contacts.begin(), contacts.end(), [](const Contact& l, const Contact& r) {
    return l.gap < r.gap || (l.gap == r.gap && (l.a < r.a || (l.a == r.a && l.b < r.b)));
  });
  return contacts;
}

std::vector<int> PersonDetector::MergeRegions(const GridPoints& grid, double merge_step,
                                              std::vector<Region>* regions) {
  std::vector<Region>& rs = *regions;
  std::vector<int> parent(rs.size());
  for (size_t id = 0; id < rs.size(); ++id) parent[id] = static_cast<int>(id);
  const auto find = [&](int id) {
    while (parent[id] != id) id = parent[id] = parent[parent[id]];
    return id;
  };
  for (const Contact& c : RegionContacts(grid, merge_step)) {
    const int a = find(c.a), b = find(c.b);
    if (a == b) continue;
    Region u = rs[a];
    const Region& r = rs[b];
    u.pixels += r.pixels;
    u.sum += r.sum;
    u.top = std::max(u.top, r.top), u.bottom = std::min(u.bottom, r.bottom);
    u.area += r.area;
    u.min1 = std::min(u.min1, r.min1), u.max1 = std::max(u.max1, r.max1);
    u.min2 = std::min(u.min2, r.min2), u.max2 = std::max(u.max2, r.max2);
    u.touches_bottom |= r.touches_bottom;
    if (std::hypot(u.max1 - u.min1, u.max2 - u.min2) > options_.max_extent_m ||
        u.area > options_.max_area_m2)
      continue;
    rs[a] = u;
    parent[b] = a;
  }
  for (int& label : label_)
    if (label >= 0) label = find(label);
  return parent;
}

int PersonDetector::ChooseRegion(const GridPoints& grid, const std::vector<Region>& regions,
                                 const std::vector<int>& parent,
                                 const std::optional<Eigen::Vector3d>& previous_centroid,
                                 bool floor_seen, PersonBlob* blob) const {
  // Width of each region's top 12 cm (the head, or raised hands).
  std::vector<double> tmin1(regions.size(), 1e9), tmax1(regions.size(), -1e9),
      tmin2(regions.size(), 1e9), tmax2(regions.size(), -1e9);
  for (size_t i = 0; i < label_.size(); ++i) {
    const int id = label_[i];
    if (id < 0 || grid.height_m[i] < regions[id].top - 0.12) continue;
    const double a = grid.point[i].dot(grid.e1), b = grid.point[i].dot(grid.e2);
    tmin1[id] = std::min(tmin1[id], a), tmax1[id] = std::max(tmax1[id], a);
    tmin2[id] = std::min(tmin2[id], b), tmax2[id] = std::max(tmax2[id], b);
  }
  int best = -1;
  double best_score = -std::numeric_limits<double>::infinity();
  for (size_t id = 0; id < regions.size(); ++id) {
    const Region& r = regions[id];
    if (parent[id] != static_cast<int>(id) || r.pixels < options_.min_region_pixels) continue;
    const double extent = std::hypot(r.max1 - r.min1, r.max2 - r.min2);
    const double top_width = std::hypot(tmax1[id] - tmin1[id], tmax2[id] - tmin2[id]);
    const bool standing =
        floor_seen ? r.top >= options_.min_top_m &&
                         (r.bottom <= options_.max_bottom_m || r.touches_bottom)
                   : r.top - r.bottom >= options_.min_top_m && r.top - r.bottom <= options_.max_height_m;
    const bool plausible = standing &&
                           extent <= options_.max_extent_m && r.area >= options_.min_area_m2 &&
                           r.area <= options_.max_area_m2 &&
                           (previous_centroid || top_width <= options_.max_top_width_m);
    if (!plausible) continue;
    ++blob->plausible_regions;
    const Eigen::Vector3d centroid = r.sum / r.pixels;
    double score = r.area;
    if (previous_centroid) {
      const double jump = (centroid - *previous_centroid).norm();
      if (jump > options_.max_jump_m) continue;
      score = -jump;
    }
    if (score > best_score) best_score = score, best = static_cast<int>(id);
  }
  return best;
}

void PersonDetector::FillBlob(const GridPoints& grid, const Region& r, int id,
                              PersonBlob* blob) const {
  blob->status = DetectStatus::kOk;
  blob->centroid = r.sum / r.pixels;
  blob->top_height_m = r.top;
  blob->bottom_height_m = r.bottom;
  blob->area_m2 = r.area;
  blob->touches_bottom = r.touches_bottom;
  blob->points.reserve(r.pixels);
  blob->pixels.reserve(r.pixels);
  for (size_t i = 0; i < label_.size(); ++i) {
    if (label_[i] != id) continue;
    blob->mask.data[i] = 255;
    blob->points.push_back(grid.point[i]);
    blob->pixels.emplace_back(static_cast<int>(i) % grid.width, static_cast<int>(i) / grid.width);
  }
}

}  // namespace reenact::capture
