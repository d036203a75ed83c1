#include "capture-client/tracker/geodesic_extremities.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
#include <unordered_map>

#include "common/error/check.h"

namespace reenact::capture {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

int64_t CellKey(int64_t x, int64_t y, int64_t z) {
  constexpr int64_t kOffset = 1 << 20;
  return ((x + kOffset) << 42) | ((y + kOffset) << 21) | (z + kOffset);
}

Eigen::Vector3i Cell(const Eigen::Vector3d& p, double size) {
  return Eigen::Vector3i(static_cast<int>(std::floor(p.x() / size)),
                         static_cast<int>(std::floor(p.y() / size)),
                         static_cast<int>(std::floor(p.z() / size)));
}

struct Graph {
  std::vector<Eigen::Vector3d> nodes;
  std::vector<std::vector<std::pair<int, double>>> edges;
};

Graph BuildGraph(const std::vector<Eigen::Vector3d>& points, double voxel_m, double neighbour_m) {
  Graph g;
  std::unordered_map<int64_t, int> voxel;
  std::vector<int> count;
  for (const Eigen::Vector3d& p : points) {
    if (!p.allFinite() || p.cwiseAbs().maxCoeff() > 1e4) continue;
    const Eigen::Vector3i c = Cell(p, voxel_m);
    const auto [it, inserted] =
        voxel.emplace(CellKey(c.x(), c.y(), c.z()), static_cast<int>(g.nodes.size()));
    if (inserted) {
      g.nodes.push_back(p);
      count.push_back(1);
    } else {
      g.nodes[it->second] += p;
      ++count[it->second];
    }
  }
  for (size_t i = 0; i < g.nodes.size(); ++i) g.nodes[i] /= count[i];
  std::unordered_map<int64_t, std::vector<int>> cells;
  for (size_t i = 0; i < g.nodes.size(); ++i) {
    const Eigen::Vector3i c = Cell(g.nodes[i], neighbour_m);
    cells[CellKey(c.x(), c.y(), c.z())].push_back(static_cast<int>(i));
  }
  g.edges.resize(g.nodes.size());
  for (size_t i = 0; i < g.nodes.size(); ++i) {
    const Eigen::Vector3i c = Cell(g.nodes[i], neighbour_m);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells.find(CellKey(c.x() + dx, c.y() + dy, c.z() + dz));
          if (it == cells.end()) continue;
          for (int j : it->second) {
            if (j == static_cast<int>(i)) continue;
            const double d = (g.nodes[i] - g.nodes[j]).norm();
            if (d <= neighbour_m) g.edges[i].emplace_back(j, d);
          }
        }
  }
  return g;
}

std::vector<double> Dijkstra(const Graph& g, int source) {
  std::vector<double> dist(g.nodes.size(), kInf);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  dist[source] = 0;
  queue.emplace(0.0, source);
  while (!queue.empty()) {
    const auto [d, i] = queue.top();
    queue.pop();
    if (d > dist[i]) continue;
    for (const auto& [j, w] : g.edges[i])
      if (d + w < dist[j]) {
        dist[j] = d + w;
        queue.emplace(dist[j], j);
      }
  }
  return dist;
}

}  // namespace

void GeodesicExtremityOptions::Check() const {
  REENACT_CHECK(voxel_m > 0 && neighbour_m > voxel_m, "voxel_m > 0 and neighbour_m > voxel_m");
  REENACT_CHECK(min_length_m >= 0 && min_separation_m > 0 && min_prominence_m >= 0,
                "min_length_m >= 0, min_separation_m > 0 and min_prominence_m >= 0");
  REENACT_CHECK(max_extremities >= 1, "max_extremities must be >= 1");
  REENACT_CHECK(head_min_rise_m >= 0, "head_min_rise_m must be >= 0");
  REENACT_CHECK(foot_max_height_ratio >= 0 && foot_max_height_ratio <= 1,
                "foot_max_height_ratio in [0, 1]");
}

std::string_view ExtremityLabelName(ExtremityLabel label) {
  switch (label) {
    case ExtremityLabel::kUnknown:
      return "unknown";
    case ExtremityLabel::kHead:
      return "head";
    case ExtremityLabel::kHand:
      return "hand";
    case ExtremityLabel::kFoot:
      return "foot";
  }
  return "unknown";
}

std::vector<const Extremity*> GeodesicExtremities::WithLabel(ExtremityLabel label) const {
  std::vector<const Extremity*> out;
  for (const Extremity& e : extremities)
    if (e.label == label) out.push_back(&e);
  return out;
}

GeodesicExtremities FindGeodesicExtremities(const std::vector<Eigen::Vector3d>& points,
                                            const std::optional<Plane3>& floor,
                                            const GeodesicExtremityOptions& options) {
  options.Check();
  GeodesicExtremities out;
  const Graph g = BuildGraph(points, options.voxel_m, options.neighbour_m);
  const int n = static_cast<int>(g.nodes.size());
  if (n == 0) return out;
  out.valid = true;
  out.nodes = n;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : g.nodes) centroid += p;
  centroid /= n;
  int centre = 0;
  for (int i = 1; i < n; ++i)
    if ((g.nodes[i] - centroid).squaredNorm() < (g.nodes[centre] - centroid).squaredNorm())
      centre = i;
  out.torso_centre = g.nodes[centre];
  const std::vector<double> dist = Dijkstra(g, centre);
  out.reachable =
      static_cast<int>(std::count_if(dist.begin(), dist.end(), [](double d) { return d < kInf; }));

  // Peaks of the geodesic distance by persistence: nodes taken farthest first, each joining
  // the components of its neighbours taken before it; where components meet, all but the
  // one with the highest peak end, their peaks' prominence = peak - the meeting node's.
  std::vector<int> order;
  for (int i = 0; i < n; ++i)
    if (dist[i] < kInf) order.push_back(i);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return dist[a] > dist[b] || (dist[a] == dist[b] && a < b); });
  std::vector<int> parent(n, -1), peak(n, -1);
  std::function<int(int)> find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::vector<int> candidates;
  for (int i : order) {
    parent[i] = i;
    peak[i] = i;
    for (const auto& [j, w] : g.edges[i]) {
      if (parent[j] < 0) continue;
      const int a = find(i), b = find(j);
      if (a == b) continue;
      const int high = dist[peak[a]] >= dist[peak[b]] ? a : b, low = high == a ? b : a;
      if (peak[low] != i && dist[peak[low]] - dist[i] >= options.min_prominence_m)
        candidates.push_back(peak[low]);
      parent[low] = high;
    }
  }
  if (!order.empty()) candidates.push_back(peak[find(order.front())]);  // the highest
  std::sort(candidates.begin(), candidates.end(),
            [&](int a, int b) { return dist[a] > dist[b] || (dist[a] == dist[b] && a < b); });
  std::vector<std::vector<double>> from_kept;
  std::vector<int> kept;
  for (int i : candidates) {
    if (static_cast<int>(kept.size()) >= options.max_extremities) break;
    if (dist[i] < options.min_length_m) continue;
    bool separated = true;
    for (const std::vector<double>& d : from_kept)
      separated = separated && d[i] >= options.min_separation_m;
    if (!separated) continue;
    kept.push_back(i);
    from_kept.push_back(Dijkstra(g, i));
  }

  // Heights in the floor's frame.
  const Eigen::Vector3d up = floor ? floor->normal.normalized() : Eigen::Vector3d(0, -1, 0);
  double base = 0;
  if (!floor) {
    base = kInf;
    for (const Eigen::Vector3d& p : g.nodes) base = std::min(base, p.dot(up));
  }
  auto height = [&](const Eigen::Vector3d& p) {
    return floor ? floor->SignedDistance(p) / floor->normal.norm() : p.dot(up) - base;
  };
  double top = 0;
  for (const Eigen::Vector3d& p : g.nodes) top = std::max(top, height(p));
  for (int i : kept) out.extremities.push_back({g.nodes[i], dist[i], height(g.nodes[i])});

  // Labels: the head, then the feet, then the hands.
  std::vector<Extremity>& ex = out.extremities;
  const double centre_height = height(out.torso_centre);
  int head = -1;
  for (int k = 0; k < static_cast<int>(ex.size()); ++k)
    if (ex[k].height_m - centre_height >= options.head_min_rise_m &&
        (head < 0 || ex[k].geodesic_m < ex[head].geodesic_m))
      head = k;
  if (head >= 0) ex[head].label = ExtremityLabel::kHead;
  std::vector<int> rest;
  for (int k = 0; k < static_cast<int>(ex.size()); ++k)
    if (k != head) rest.push_back(k);
  std::sort(rest.begin(), rest.end(),
            [&](int a, int b) { return ex[a].height_m < ex[b].height_m; });
  int feet = 0;
  for (int k : rest)
    if (feet < 2 && ex[k].height_m <= options.foot_max_height_ratio * top) {
      ex[k].label = ExtremityLabel::kFoot;
      ++feet;
    }
  int hands = 0;
  for (Extremity& e : ex)  // farthest first
    if (e.label == ExtremityLabel::kUnknown && hands < 2) {
      e.label = ExtremityLabel::kHand;
      ++hands;
    }
  return out;
}

}  // namespace reenact::capture
