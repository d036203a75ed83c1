#include "common/texture/texture_graph_index.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <random>

#include "common/error/check.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace reenact {
namespace {

constexpr uint16_t kPadBit = 1u << 15;
constexpr int kMaxLevel = 32;
constexpr int kRepairSlots = 2;  // bottom-layer links beyond 2M, for ConnectUnreachable

bool Better(const TextureCandidate& x, const TextureCandidate& y) {
  return x.cost < y.cost || (x.cost == y.cost && x.frame < y.frame);
}

}  // namespace

// Marks of the nodes one search has reached: an epoch per node, so that starting a new
// search costs nothing.
class TextureGraphIndex::Visited {
 public:
  void Start(size_t count) {
    if (mark_.size() < count) mark_.assign(count, 0), epoch_ = 0;
    if (++epoch_ == 0) std::fill(mark_.begin(), mark_.end(), 0), epoch_ = 1;
  }
  bool Insert(int node) {
    if (mark_[node] == epoch_) return false;
    mark_[node] = epoch_;
    return true;
  }

 private:
  std::vector<uint32_t> mark_;
  uint32_t epoch_ = 0;
};

namespace {

// Eq. 5 in single precision over the padded layout; `both` marks the slots present in both
// points (the pad always: it adds |0 - 0| = 0).
template <typename Point>
float PointCost(const Point& a, const Point& b, uint16_t both, float missing) {
#if defined(__SSE2__)
  alignas(16) static constexpr uint32_t kLanes[16][4] = {
      {0, 0, 0, 0},     {~0u, 0, 0, 0},     {0, ~0u, 0, 0},     {~0u, ~0u, 0, 0},
      {0, 0, ~0u, 0},   {~0u, 0, ~0u, 0},   {0, ~0u, ~0u, 0},   {~0u, ~0u, ~0u, 0},
      {0, 0, 0, ~0u},   {~0u, 0, 0, ~0u},   {0, ~0u, 0, ~0u},   {~0u, ~0u, 0, ~0u},
      {0, 0, ~0u, ~0u}, {~0u, 0, ~0u, ~0u}, {0, ~0u, ~0u, ~0u}, {~0u, ~0u, ~0u, ~0u}};
  const __m128 m = _mm_set1_ps(missing);
  __m128 sum = _mm_setzero_ps();
  for (int c = 0; c < 16; c += 4) {
    const __m128 dx = _mm_sub_ps(_mm_load_ps(a.x + c), _mm_load_ps(b.x + c));
    const __m128 dy = _mm_sub_ps(_mm_load_ps(a.y + c), _mm_load_ps(b.y + c));
    const __m128 dz = _mm_sub_ps(_mm_load_ps(a.z + c), _mm_load_ps(b.z + c));
    const __m128 norm = _mm_sqrt_ps(
        _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz)));
    const __m128 lanes = _mm_load_ps(reinterpret_cast<const float*>(kLanes[(both >> c) & 15]));
    sum = _mm_add_ps(sum, _mm_or_ps(_mm_and_ps(lanes, norm), _mm_andnot_ps(lanes, m)));
  }
  sum = _mm_add_ps(sum, _mm_movehl_ps(sum, sum));
  sum = _mm_add_ss(sum, _mm_shuffle_ps(sum, sum, 1));
  return _mm_cvtss_f32(sum);
#else
  float sum = 0;
  for (int j = 0; j < 16; ++j) {
    const float dx = a.x[j] - b.x[j], dy = a.y[j] - b.y[j], dz = a.z[j] - b.z[j];
    sum += (both >> j) & 1 ? std::sqrt(dx * dx + dy * dy + dz * dz) : missing;
  }
  return sum;
#endif
}

}  // namespace

void TextureGraphIndexOptions::Check() const {
  REENACT_CHECK(max_neighbors >= 2, "max_neighbors must be >= 2");
  REENACT_CHECK(build_beam >= max_neighbors, "build_beam must be >= max_neighbors");
  REENACT_CHECK(std::isfinite(missing_joint_cost_m) && missing_joint_cost_m >= 0,
                "missing_joint_cost_m must be finite and >= 0");
}

void TextureGraphSearch::Check() const { REENACT_CHECK(beam >= 1, "beam must be >= 1"); }

TextureGraphIndex::TextureGraphIndex(std::span<const Skeleton> stored, std::span<const bool> usable,
                                     const TextureGraphIndexOptions& options) {
  options.Check();
  stored_count_ = static_cast<int>(stored.size());
  max_neighbors_ = options.max_neighbors;
  build_missing_cost_ = static_cast<float>(options.missing_joint_cost_m);
  NeckOffsetTable table = MakeNeckOffsetTable(stored, usable);
  frame_ = std::move(table.frame);
  offset_ = std::move(table.offset);
  present_ = std::move(table.present);
  for (size_t row = 0; row < frame_.size(); ++row) {
    present_[row] |= kPadBit;
    point_.push_back(ToPoint(&offset_[row * kNeckOffsetDims]));
  }
  const int count = indexed_count();
  links0_.assign(static_cast<size_t>(count) * Links0Stride(), 0);
  upper_.resize(count);
  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double level_scale = 1.0 / std::log(static_cast<double>(max_neighbors_));
  Visited visited;
  for (int node = 0; node < count; ++node) {
    const double u = 1.0 - unit(rng);  // in (0, 1]
    const int level = std::min(kMaxLevel, static_cast<int>(-std::log(u) * level_scale));
    upper_[node].assign(static_cast<size_t>(level) * (max_neighbors_ + 1), 0);
    Insert(node, level, options.build_beam, visited);
  }
  if (count > 0) ConnectUnreachable(options.build_beam, visited);
}

int TextureGraphIndex::Links0Stride() const { return 2 * max_neighbors_ + kRepairSlots + 1; }

void TextureGraphIndex::ConnectUnreachable(int build_beam, Visited& visited) {
  const int count = indexed_count();
  std::vector<char> reached(count, 0);
  std::vector<int> stack;
  auto flood = [&](int from) {
    reached[from] = 1;
    for (stack.assign(1, from); !stack.empty();) {
      const int n = stack.back();
      stack.pop_back();
      for (int l : Links(n, 0))
        if (!reached[l]) reached[l] = 1, stack.push_back(l);
    }
  };
  auto has_slot = [&](int n) {
    return static_cast<int>(Links(n, 0).size()) < 2 * max_neighbors_ + kRepairSlots;
  };
  flood(entry_);
  for (int u = 0; u < count; ++u) {
    if (reached[u]) continue;
    // The nearest reached frames (the search from the entry sees only reached ones) with a
    // free repair slot, else any reached frame with one: there always is one, since each
    // repair uses one slot and brings in a frame whose own repair slots are free.
    const Found entry{Cost(entry_, u), entry_};
    int host = -1;
    for (const Found& f : SearchLayer(point_[u], present_[u], build_missing_cost_, {&entry, 1}, 0,
                                      build_beam, visited))
      if (has_slot(f.node)) {
        host = f.node;
        break;
      }
    for (int n = 0; host < 0 && n < count; ++n)
      if (reached[n] && has_slot(n)) host = n;
    REENACT_CHECK(host >= 0, "no frame with a free link slot (cannot happen)");
    std::vector<int> links(Links(host, 0).begin(), Links(host, 0).end());
    links.push_back(u);
    SetLinks(host, 0, links);
    flood(u);
  }
}

TextureGraphIndex::Point TextureGraphIndex::ToPoint(const double* o) {
  Point p;
  for (int j = 0; j < 16; ++j) {
    p.x[j] = j < kNeckOffsetSlots ? static_cast<float>(o[3 * j]) : 0.0f;
    p.y[j] = j < kNeckOffsetSlots ? static_cast<float>(o[3 * j + 1]) : 0.0f;
    p.z[j] = j < kNeckOffsetSlots ? static_cast<float>(o[3 * j + 2]) : 0.0f;
  }
  return p;
}

std::span<const int> TextureGraphIndex::Links(int node, int layer) const {
  const int* block = layer == 0
                         ? &links0_[static_cast<size_t>(node) * Links0Stride()]
                         : &upper_[node][static_cast<size_t>(layer - 1) * (max_neighbors_ + 1)];
  return {block + 1, static_cast<size_t>(block[0])};
}

void TextureGraphIndex::SetLinks(int node, int layer, std::span<const int> links) {
  int* block = layer == 0 ? &links0_[static_cast<size_t>(node) * Links0Stride()]
                          : &upper_[node][static_cast<size_t>(layer - 1) * (max_neighbors_ + 1)];
  block[0] = static_cast<int>(links.size());
  std::copy(links.begin(), links.end(), block + 1);
}

float TextureGraphIndex::Cost(int a, int b) const {
  return PointCost(point_[a], point_[b], present_[a] & present_[b], build_missing_cost_);
}

TextureGraphIndex::Found TextureGraphIndex::Descend(const Point& q, uint16_t q_mask,
                                                    float missing_cost, int to_layer) const {
  Found current{PointCost(q, point_[entry_], q_mask & present_[entry_], missing_cost), entry_};
  for (int layer = top_level_; layer > to_layer; --layer) {
    for (bool moved = true; moved;) {
      moved = false;
      for (int n : Links(current.node, layer)) {
        const Found next{PointCost(q, point_[n], q_mask & present_[n], missing_cost), n};
        if (next < current) current = next, moved = true;
      }
    }
  }
  return current;
}

std::vector<TextureGraphIndex::Found> TextureGraphIndex::SearchLayer(
    const Point& q, uint16_t q_mask, float missing_cost, std::span<const Found> entries, int layer,
    int beam, Visited& visited) const {
  visited.Start(point_.size());
  std::priority_queue<Found, std::vector<Found>, std::greater<Found>> frontier;  // nearest on top
  std::priority_queue<Found> kept;                                               // farthest on top
  for (const Found& entry : entries) {
    if (!visited.Insert(entry.node)) continue;
    frontier.push(entry);
    kept.push(entry);
    if (kept.size() > static_cast<size_t>(beam)) kept.pop();
  }
  while (!frontier.empty()) {
    const Found current = frontier.top();
    if (kept.size() >= static_cast<size_t>(beam) && kept.top() < current) break;
    frontier.pop();
    const std::span<const int> links = Links(current.node, layer);
    for (size_t i = 0; i < links.size(); ++i) {
      if (i + 1 < links.size()) {
        const char* next = reinterpret_cast<const char*>(&point_[links[i + 1]]);
        __builtin_prefetch(next);
        __builtin_prefetch(next + 64);
        __builtin_prefetch(next + 128);
      }
      const int n = links[i];
      if (!visited.Insert(n)) continue;
      const Found found{PointCost(q, point_[n], q_mask & present_[n], missing_cost), n};
      if (kept.size() < static_cast<size_t>(beam) || found < kept.top()) {
        frontier.push(found);
        kept.push(found);
        if (kept.size() > static_cast<size_t>(beam)) kept.pop();
      }
    }
  }
  std::vector<Found> out(kept.size());
  for (size_t i = out.size(); i-- > 0; kept.pop()) out[i] = kept.top();
  return out;
}

std::vector<int> TextureGraphIndex::SelectNeighbors(std::vector<Found> candidates,
                                                    int count) const {
  std::sort(candidates.begin(), candidates.end());
  std::vector<int> kept;
  for (const Found& c : candidates) {
    if (static_cast<int>(kept.size()) >= count) break;
    const bool diverse =
        std::none_of(kept.begin(), kept.end(), [&](int k) { return Cost(c.node, k) < c.cost; });
    if (diverse) kept.push_back(c.node);
  }
  return kept;
}

void TextureGraphIndex::Insert(int node, int level, int build_beam, Visited& visited) {
  if (entry_ < 0) {
    entry_ = node;
    top_level_ = level;
    return;
  }
  const Point& q = point_[node];
  const uint16_t mask = present_[node];
  Found entry = Descend(q, mask, build_missing_cost_, level);
  for (int layer = std::min(level, top_level_); layer >= 0; --layer) {
    const int capacity = layer == 0 ? 2 * max_neighbors_ : max_neighbors_;
    const std::vector<Found> found =
        SearchLayer(q, mask, build_missing_cost_, {&entry, 1}, layer, build_beam, visited);
    const std::vector<int> neighbors = SelectNeighbors(found, max_neighbors_);
    SetLinks(node, layer, neighbors);
    for (int n : neighbors) {
      const std::span<const int> links = Links(n, layer);
      std::vector<int> grown(links.begin(), links.end());
      grown.push_back(node);
      if (static_cast<int>(grown.size()) <= capacity) {
        SetLinks(n, layer, grown);
        continue;
      }
      std::vector<Found> candidates;
      for (int g : grown) candidates.push_back({Cost(n, g), g});
      SetLinks(n, layer, SelectNeighbors(std::move(candidates), capacity));
    }
    entry = found.front();
  }
  if (level > top_level_) {
    entry_ = node;
    top_level_ = level;
  }
}

std::vector<TextureCandidate> TextureGraphIndex::Rank(const Skeleton& viewer,
                                                      const TextureSelectionOptions& options,
                                                      const TextureGraphSearch& search) const {
  options.Check();
  search.Check();
  if (entry_ < 0 || !viewer.Has(Joint::kNeck)) return {};
  double exact[kNeckOffsetDims];
  const uint16_t exact_mask = WriteNeckOffsets(viewer, exact);
  const Point q = ToPoint(exact);
  const uint16_t mask = exact_mask | kPadBit;
  const float missing = static_cast<float>(options.missing_joint_cost_m);

  // Seeded from the entry too: every frame is reachable from it (ConnectUnreachable), so a
  // beam as wide as the index visits every frame.
  thread_local Visited visited;
  const Found seeds[] = {Descend(q, mask, missing, 0),
                         {PointCost(q, point_[entry_], mask & present_[entry_], missing), entry_}};
  const std::vector<Found> found =
      SearchLayer(q, mask, missing, seeds, 0, std::max(search.beam, options.top_k), visited);
  std::vector<TextureCandidate> ranked;
  ranked.reserve(found.size());
  for (const Found& f : found)
    ranked.push_back(
        {frame_[f.node],
         NeckOffsetCost(exact, exact_mask, &offset_[static_cast<size_t>(f.node) * kNeckOffsetDims],
                        present_[f.node], options.missing_joint_cost_m)});
  std::sort(ranked.begin(), ranked.end(), Better);
  ranked.resize(std::min(ranked.size(), static_cast<size_t>(options.top_k)));
  return ranked;
}

}  // namespace reenact
