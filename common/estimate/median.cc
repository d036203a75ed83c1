#include "common/estimate/median.h"

#include <algorithm>
#include <cmath>

#include "common/error/check.h"

namespace reenact {

double Median(std::vector<double> v) {
  REENACT_CHECK(!v.empty(), "median of an empty set");
  const size_t n = v.size();
  std::nth_element(v.begin(), v.begin() + n / 2, v.end());
  const double upper = v[n / 2];
  if (n % 2) return upper;
  return 0.5 * (upper + *std::max_element(v.begin(), v.begin() + n / 2));
}

double UpperMedian(std::vector<double> v) {
  REENACT_CHECK(!v.empty(), "median of an empty set");
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

double Percentile(std::vector<double> v, double q) {
  REENACT_CHECK(!v.empty(), "percentile of an empty set");
  REENACT_CHECK(q >= 0 && q <= 1, "percentile's share must be in [0, 1]");
  const double rank = std::ceil(q * static_cast<double>(v.size()));
  const size_t k = rank < 1 ? 0 : static_cast<size_t>(rank) - 1;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace reenact
