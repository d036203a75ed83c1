#include "capture-client/tracker/gap_ratio.h"

#include <algorithm>
#include <cmath>

#include "common/error/check.h"

namespace reenact::capture {

double GapRatio(std::optional<double> t, std::optional<double> t1, std::optional<double> t0,
                double max_ratio) {
  REENACT_CHECK(max_ratio >= 1 && std::isfinite(max_ratio), "max_ratio must be >= 1");
  if (!t || !t1 || !t0) return 1;
  const double gap = *t - *t1, last = *t1 - *t0;
  if (!std::isfinite(gap) || !std::isfinite(last) || !(gap > 0) || !(last > 0)) return 1;
  const double ratio = gap / last;
  if (std::abs(ratio - 1) < 1e-6) return 1;
  return std::min(ratio, max_ratio);
}

}  // namespace reenact::capture
