#include "common/texture/texture_index.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <queue>

#include "common/error/check.h"

namespace reenact {
namespace {

// The candidate order of RankTextureFrames: ascending cost, then ascending frame.
bool Better(const TextureCandidate& x, const TextureCandidate& y) {
  return x.cost < y.cost || (x.cost == y.cost && x.frame < y.frame);
}

// A cost bound beyond which nothing can reach the top k: the k-th cost plus a margin far
// above the rounding of a 16-term sum of norms.
double PruneAbove(double kth_cost) { return kth_cost + 1e-9 * kth_cost + 1e-12; }

}  // namespace

void TextureIndexOptions::Check() const { REENACT_CHECK(leaf_size >= 1, "leaf_size must be >= 1"); }

TextureIndex::TextureIndex(std::span<const Skeleton> stored, std::span<const bool> usable,
                           const TextureIndexOptions& options) {
  options.Check();
  stored_count_ = static_cast<int>(stored.size());
  NeckOffsetTable table = MakeNeckOffsetTable(stored, usable);
  frame_ = std::move(table.frame);
  offset_ = std::move(table.offset);
  present_ = std::move(table.present);
  if (frame_.empty()) return;
  nodes_.reserve(2 * frame_.size() / options.leaf_size + 2);
  Build(0, static_cast<int>(frame_.size()), options.leaf_size);
}

int TextureIndex::Build(int begin, int end, int leaf_size) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  FitNode(nodes_[id], begin, end);
  if (end - begin <= leaf_size) return id;
  const int mid = begin + (end - begin) / 2;
  if (!SplitAt(begin, mid, end, nodes_[id].centre)) return id;  // duplicates: one leaf
  const int left = Build(begin, mid, leaf_size);
  const int right = Build(mid, end, leaf_size);
  nodes_[id].left = left;
  nodes_[id].right = right;
  return id;
}

void TextureIndex::FitNode(Node& node, int begin, int end) const {
  node.begin = begin;
  node.end = end;
  std::fill(std::begin(node.lo), std::end(node.lo), std::numeric_limits<double>::infinity());
  std::fill(std::begin(node.hi), std::end(node.hi), -std::numeric_limits<double>::infinity());
  std::fill(std::begin(node.centre), std::end(node.centre), 0.0);
  std::fill(std::begin(node.radius), std::end(node.radius), 0.0);
  node.ball_radius = 0;
  int count[kOffsets] = {};
  for (int f = begin; f < end; ++f) {
    node.present_mask |= present_[f];
    node.missing_mask |= static_cast<uint16_t>(~present_[f] & ((1u << kOffsets) - 1));
    const double* o = &offset_[static_cast<size_t>(f) * kDims];
    for (int j = 0; j < kOffsets; ++j) {
      if (!(present_[f] & (1u << j))) continue;
      ++count[j];
      for (int d = 3 * j; d < 3 * j + 3; ++d) {
        node.lo[d] = std::min(node.lo[d], o[d]);
        node.hi[d] = std::max(node.hi[d], o[d]);
        node.centre[d] += o[d];
      }
    }
  }
  for (int j = 0; j < kOffsets; ++j)
    for (int d = 3 * j; d < 3 * j + 3; ++d) node.centre[d] /= std::max(count[j], 1);
  for (int f = begin; f < end; ++f) {
    const double* o = &offset_[static_cast<size_t>(f) * kDims];
    double sum = 0;
    for (int j = 0; j < kOffsets; ++j) {
      if (!(present_[f] & (1u << j))) continue;
      const double r = (Eigen::Map<const Eigen::Vector3d>(&o[3 * j]) -
                        Eigen::Map<const Eigen::Vector3d>(&node.centre[3 * j]))
                           .norm();
      node.radius[j] = std::max(node.radius[j], r);
      sum += r;
    }
    node.ball_radius = std::max(node.ball_radius, sum);
  }
}

bool TextureIndex::SplitAt(int begin, int mid, int end, const double* centre) {
  auto distance = [&](int f, const double* x) {
    const double* o = &offset_[static_cast<size_t>(f) * kDims];
    double sum = 0;
    for (int d = 0; d < kDims; d += 3)
      sum +=
          std::sqrt((o[d] - x[d]) * (o[d] - x[d]) + (o[d + 1] - x[d + 1]) * (o[d + 1] - x[d + 1]) +
                    (o[d + 2] - x[d + 2]) * (o[d + 2] - x[d + 2]));
    return sum;
  };
  auto farthest = [&](const double* x) {
    int best = begin;
    double best_distance = -1;
    for (int f = begin; f < end; ++f)
      if (const double dist = distance(f, x); dist > best_distance) best_distance = dist, best = f;
    return std::pair{best, best_distance};
  };
  const int a = farthest(centre).first;
  double pa[kDims], pb[kDims];
  std::copy_n(&offset_[static_cast<size_t>(a) * kDims], kDims, pa);
  const auto [b, spread] = farthest(pa);
  if (spread == 0) return false;
  std::copy_n(&offset_[static_cast<size_t>(b) * kDims], kDims, pb);
  std::vector<double> key(end - begin);
  for (int f = begin; f < end; ++f) key[f - begin] = distance(f, pa) - distance(f, pb);

  std::vector<int> order(end - begin);
  std::iota(order.begin(), order.end(), begin);
  std::nth_element(order.begin(), order.begin() + (mid - begin), order.end(),
                   [&](int x, int y) { return key[x - begin] < key[y - begin]; });
  Permute(begin, order);
  return true;
}

void TextureIndex::Permute(int begin, const std::vector<int>& order) {
  std::vector<int> frames(order.size());
  std::vector<double> offsets(order.size() * kDims);
  std::vector<uint16_t> present(order.size());
  for (size_t r = 0; r < order.size(); ++r) {
    frames[r] = frame_[order[r]];
    present[r] = present_[order[r]];
    std::copy_n(&offset_[static_cast<size_t>(order[r]) * kDims], kDims, &offsets[r * kDims]);
  }
  std::copy(frames.begin(), frames.end(), frame_.begin() + begin);
  std::copy(present.begin(), present.end(), present_.begin() + begin);
  std::copy(offsets.begin(), offsets.end(), offset_.begin() + static_cast<size_t>(begin) * kDims);
}

double TextureIndex::LowerBound(const Node& node, const double* q, uint16_t query_mask,
                                double missing_cost) {
  double bound = 0;      // sum of per-joint bounds
  double to_centre = 0;  // L2,1 distance to the centre over the joints both have
  for (int j = 0; j < kOffsets; ++j) {
    const uint16_t bit = static_cast<uint16_t>(1u << j);
    if (!(query_mask & bit) || !(node.present_mask & bit)) {
      bound += missing_cost;
      continue;
    }
    double squared = 0, centre_squared = 0;
    for (int d = 3 * j; d < 3 * j + 3; ++d) {
      const double gap = std::max({node.lo[d] - q[d], q[d] - node.hi[d], 0.0});
      squared += gap * gap;
      centre_squared += (q[d] - node.centre[d]) * (q[d] - node.centre[d]);
    }
    const double centre_distance = std::sqrt(centre_squared);
    to_centre += centre_distance;
    const double distance = std::max(std::sqrt(squared), centre_distance - node.radius[j]);
    bound += (node.missing_mask & bit) ? std::min(distance, missing_cost) : distance;
  }
  if (node.missing_mask == 0) {
    // Triangle inequality of the L2,1 metric over the query's joints.
    const int absent = kOffsets - std::popcount(query_mask);
    bound = std::max(bound, to_centre - node.ball_radius + absent * missing_cost);
  }
  return bound;
}

std::vector<TextureCandidate> TextureIndex::Rank(const Skeleton& viewer,
                                                 const TextureSelectionOptions& options,
                                                 TextureIndexStats* stats) const {
  options.Check();
  if (stats) *stats = {};
  if (nodes_.empty() || !viewer.Has(Joint::kNeck)) return {};
  const double m = options.missing_joint_cost_m;

  double q[kDims];
  const uint16_t query_mask = WriteNeckOffsets(viewer, q);

  const size_t k = std::min(static_cast<size_t>(options.top_k), frame_.size());
  std::vector<TextureCandidate> best;  // max-heap under Better: best.front() is the k-th
  best.reserve(k + 1);
  auto bound = [&] {
    return best.size() < k ? std::numeric_limits<double>::infinity()
                           : PruneAbove(best.front().cost);
  };

  int64_t evaluated = 0, visited = 0;
  auto evaluate_leaf = [&](const Node& node) {
    for (int f = node.begin; f < node.end; ++f) {
      ++evaluated;
      const double limit = bound();
      const double cost = NeckOffsetCost(q, query_mask, &offset_[static_cast<size_t>(f) * kDims],
                                         present_[f], m, limit);
      if (cost > limit) continue;
      const TextureCandidate candidate{frame_[f], cost};
      if (best.size() < k) {
        best.push_back(candidate);
        std::push_heap(best.begin(), best.end(), Better);
      } else if (Better(candidate, best.front())) {
        std::pop_heap(best.begin(), best.end(), Better);
        best.back() = candidate;
        std::push_heap(best.begin(), best.end(), Better);
      }
    }
  };

  // A greedy dive to the leaf of smallest bound gives a first k-th cost early, then a
  // best-first search in ascending lower bound until the bound exceeds the k-th cost.
  using Entry = std::pair<double, int>;  // (lower bound, node)
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  int id = 0;
  for (; nodes_[id].left >= 0; ++visited) {
    const Node& node = nodes_[id];
    const double left = LowerBound(nodes_[node.left], q, query_mask, m);
    const double right = LowerBound(nodes_[node.right], q, query_mask, m);
    queue.emplace(std::max(left, right), left <= right ? node.right : node.left);
    id = left <= right ? node.left : node.right;
  }
  ++visited;
  evaluate_leaf(nodes_[id]);
  while (!queue.empty()) {
    const auto [lb, next] = queue.top();
    queue.pop();
    if (lb > bound()) break;
    ++visited;
    const Node& node = nodes_[next];
    if (node.left < 0) {
      evaluate_leaf(node);
      continue;
    }
    for (int child : {node.left, node.right}) {
      const double child_lb = LowerBound(nodes_[child], q, query_mask, m);
      if (child_lb <= bound()) queue.emplace(child_lb, child);
    }
  }
  if (stats) *stats = {evaluated, visited};
  std::sort_heap(best.begin(), best.end(), Better);
  return best;
}

}  // namespace reenact
