#pragma once
// Medians and percentiles of a sample (taken by value: reordered in place, O(n) by selection).

#include <vector>

namespace reenact {

// The middle value; for an even count the mean of the two middle values.
// Precondition (CHECK): v is not empty.
double Median(std::vector<double> v);

// The value at index n / 2 in ascending order: the middle value, or for an even count the
// larger of the two middle values (always one of the samples).
// Precondition (CHECK): v is not empty.
double UpperMedian(std::vector<double> v);

// The nearest-rank q-quantile: the smallest sample that at least a share q of the samples do
// not exceed, i.e. the value at index ceil(q * n) - 1 in ascending order (index 0 for q = 0).
// Preconditions (CHECK): v is not empty, 0 <= q <= 1.
double Percentile(std::vector<double> v, double q);

}  // namespace reenact
