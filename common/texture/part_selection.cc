#include "common/texture/part_selection.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/error/check.h"

namespace reenact {
namespace {

using J = Joint;

struct JointSet {
  std::array<Joint, kMaxPartJoints> joints;
  int count;
};

// Per part: its own joints (a, b as PartJoints), then the neighbours that fix its turn.
constexpr std::array<JointSet, kBodyPartCount> kPartJoints = {{
    {{J::kHead, J::kNeck, J::kLeftShoulder, J::kRightShoulder}, 4},
    {{J::kNeck, J::kTorso, J::kLeftShoulder, J::kRightShoulder, J::kHead}, 5},
    {{J::kTorso, J::kWaist, J::kLeftHip, J::kRightHip, J::kNeck}, 5},
    {{J::kLeftShoulder, J::kLeftElbow, J::kLeftHand, J::kNeck, J::kTorso}, 5},
    {{J::kLeftElbow, J::kLeftHand, J::kLeftShoulder, J::kNeck}, 4},
    {{J::kRightShoulder, J::kRightElbow, J::kRightHand, J::kNeck, J::kTorso}, 5},
    {{J::kRightElbow, J::kRightHand, J::kRightShoulder, J::kNeck}, 4},
    {{J::kLeftHip, J::kLeftKnee, J::kLeftFoot, J::kWaist, J::kRightHip}, 5},
    {{J::kLeftKnee, J::kLeftFoot, J::kLeftHip, J::kWaist}, 4},
    {{J::kRightHip, J::kRightKnee, J::kRightFoot, J::kWaist, J::kLeftHip}, 5},
    {{J::kRightKnee, J::kRightFoot, J::kRightHip, J::kWaist}, 4},
}};

// Rows of the look frame of a part: z along the ray to the axis midpoint m, x along the
// part's axis u with the ray's component removed, y = z x x. Fallbacks (defined, not NaN):
// m at the camera centre -> z = +z; u along the ray -> x from the camera's x (or y) axis.
Eigen::Matrix3d LookFrame(const Eigen::Vector3d& m, const Eigen::Vector3d& u) {
  const double norm = m.norm();
  const Eigen::Vector3d z = norm > 1e-9 ? Eigen::Vector3d(m / norm) : Eigen::Vector3d::UnitZ();
  Eigen::Vector3d x = u - u.dot(z) * z;
  if (!(x.norm() > 1e-6 * std::max(1.0, u.norm()))) {
    x = Eigen::Vector3d::UnitX() - z.x() * z;
    if (x.norm() < 0.1) x = Eigen::Vector3d::UnitY() - z.y() * z;
  }
  x.normalize();
  Eigen::Matrix3d rows;
  rows.row(0) = x.transpose();
  rows.row(1) = z.cross(x).transpose();
  rows.row(2) = z.transpose();
  return rows;
}

double DescriptorCost(const PartDescriptor& q, const PartDescriptor& o, int count,
                      double missing_cost) {
  double cost = 0;
  for (int i = 0; i < count; ++i) {
    const uint8_t bit = static_cast<uint8_t>(1u << i);
    cost +=
        (q.present & bit) && (o.present & bit) ? (q.offset[i] - o.offset[i]).norm() : missing_cost;
  }
  return cost;
}

}  // namespace

std::span<const Joint> PartDescriptorJoints(BodyPart part) {
  const JointSet& set = kPartJoints.at(Index(part));
  return {set.joints.data(), static_cast<size_t>(set.count)};
}

void PartSelectionOptions::Check() const {
  REENACT_CHECK(top_k >= 1 && top_k <= 8, "part selection top_k must be in [1, 8]");
  REENACT_CHECK(std::isfinite(missing_joint_cost_m) && missing_joint_cost_m >= 0,
                "missing_joint_cost_m must be finite and >= 0");
  REENACT_CHECK(hysteresis >= 0 && hysteresis < 1, "hysteresis must be in [0, 1)");
  REENACT_CHECK(fallback_k >= 0 && fallback_k <= 8, "part selection fallback_k must be in [0, 8]");
}

std::optional<PartDescriptor> DescribePart(BodyPart part, const Skeleton& skeleton) {
  if (!skeleton.HasPart(part)) return std::nullopt;
  const std::span<const Joint> joints = PartDescriptorJoints(part);
  const Eigen::Vector3d m = 0.5 * (skeleton[joints[0]] + skeleton[joints[1]]);
  const Eigen::Matrix3d look = LookFrame(m, skeleton[joints[1]] - skeleton[joints[0]]);
  PartDescriptor d;
  for (size_t i = 0; i < joints.size(); ++i) {
    if (!skeleton.Has(joints[i])) {
      d.offset[i].setZero();
      continue;
    }
    d.offset[i] = look * (skeleton[joints[i]] - m);
    d.present |= static_cast<uint8_t>(1u << i);
  }
  return d;
}

PartTextureIndex::PartTextureIndex(std::span<const Skeleton> stored,
                                   std::span<const uint16_t> part_allowed,
                                   std::span<const PartCoverages> coverage)
    : stored_count_(static_cast<int>(stored.size())) {
  REENACT_CHECK(part_allowed.empty() || part_allowed.size() == stored.size(),
                "part_allowed needs one mask per stored skeleton");
  REENACT_CHECK(coverage.empty() || coverage.size() == stored.size(),
                "coverage needs one entry per stored skeleton");
  for (int p = 0; p < kBodyPartCount; ++p) {
    for (int n = 0; n < stored_count_; ++n) {
      if (!part_allowed.empty() && !(part_allowed[n] & (1u << p))) continue;
      if (auto d = DescribePart(static_cast<BodyPart>(p), stored[n]))
        rows_[p].push_back({n, *d, coverage.empty() ? PartCoverage{0} : coverage[n][p]});
    }
  }
}

std::optional<double> PartTextureIndex::Cost(BodyPart part, const Skeleton& viewer_skeleton, int n,
                                             double missing_joint_cost_m) const {
  const auto q = DescribePart(part, viewer_skeleton);
  if (!q) return std::nullopt;
  const std::vector<Row>& rows = rows_.at(Index(part));
  const auto it = std::lower_bound(rows.begin(), rows.end(), n,
                                   [](const Row& r, int frame) { return r.frame < frame; });
  if (it == rows.end() || it->frame != n) return std::nullopt;
  return DescriptorCost(*q, it->descriptor, static_cast<int>(PartDescriptorJoints(part).size()),
                        missing_joint_cost_m);
}

void PartTextureIndex::AppendFallbacks(int p, int fallback_k, std::span<const PartCandidate> scored,
                                       std::vector<PartCandidate>& chosen) const {
  const std::vector<Row>& rows = rows_[p];
  const auto coverage_of = [&rows](int frame) {
    const auto it = std::lower_bound(rows.begin(), rows.end(), frame,
                                     [](const Row& r, int f) { return r.frame < f; });
    return it != rows.end() && it->frame == frame ? it->coverage : PartCoverage{0};
  };
  PartCoverage uncovered = kFullCoverage;
  for (const PartCandidate& c : chosen) uncovered &= ~coverage_of(c.frame);
  for (int f = 0; f < fallback_k && uncovered != 0; ++f) {
    const PartCandidate* best = nullptr;
    int best_gain = 0;
    for (const PartCandidate& c : scored) {
      const int gain = CoveredCells(coverage_of(c.frame) & uncovered);
      if (gain > best_gain ||
          (gain == best_gain && best && gain > 0 &&
           (c.cost < best->cost || (c.cost == best->cost && c.frame < best->frame)))) {
        best = &c;
        best_gain = gain;
      }
    }
    if (!best) break;
    chosen.push_back({best->frame, best->cost, 0.0, true});
    uncovered &= ~coverage_of(best->frame);
  }
}

PartCandidates PartTextureIndex::Select(const Skeleton& viewer_skeleton,
                                        const PartSelectionOptions& options,
                                        PartSelectionHistory* history) const {
  options.Check();
  PartCandidates out;
  std::vector<PartCandidate> scored;
  for (int p = 0; p < kBodyPartCount; ++p) {
    const BodyPart part = static_cast<BodyPart>(p);
    const auto q = DescribePart(part, viewer_skeleton);
    const std::vector<Row>& rows = rows_[p];
    if (!q || rows.empty()) {
      if (history) history->previous[p].clear();
      continue;
    }
    const int count = static_cast<int>(PartDescriptorJoints(part).size());
    const std::vector<int> none;
    const std::vector<int>& previous = history ? history->previous[p] : none;
    scored.clear();
    for (const Row& row : rows) {
      double cost = DescriptorCost(*q, row.descriptor, count, options.missing_joint_cost_m);
      if (std::find(previous.begin(), previous.end(), row.frame) != previous.end())
        cost *= 1.0 - options.hysteresis;
      scored.push_back({row.frame, cost, 0.0});
    }
    const size_t keep = std::min(scored.size(), static_cast<size_t>(options.top_k) + 1);
    std::partial_sort(scored.begin(), scored.begin() + static_cast<std::ptrdiff_t>(keep),
                      scored.end(), [](const PartCandidate& a, const PartCandidate& b) {
                        return a.cost < b.cost || (a.cost == b.cost && a.frame < b.frame);
                      });
    const size_t k = std::min(scored.size(), static_cast<size_t>(options.top_k));
    double threshold = 0;
    if (keep > k) {
      threshold = scored[k].cost;
    } else {
      threshold = 2.0 * scored[k - 1].cost + 1e-3;
    }
    std::vector<PartCandidate>& chosen = out[p];
    chosen.assign(scored.begin(), scored.begin() + static_cast<std::ptrdiff_t>(k));
    double sum = 0;
    for (PartCandidate& c : chosen) {
      c.weight = threshold > 0 ? std::max(0.0, 1.0 - c.cost / threshold) : 0.0;
      sum += c.weight;
    }
    for (PartCandidate& c : chosen) c.weight = sum > 0 ? c.weight / sum : 1.0 / chosen.size();
    if (history) {
      history->previous[p].clear();
      for (const PartCandidate& c : chosen) history->previous[p].push_back(c.frame);
    }
    if (options.fallback_k > 0) AppendFallbacks(p, options.fallback_k, scored, chosen);
  }
  return out;
}

}  // namespace reenact
