#include "common/estimate/median.h"

#include <algorithm>

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

}  // namespace reenact
