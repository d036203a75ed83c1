#pragma once
// Joint error by the tracker's reported confidence, for `reenact-eval tracker`'s
// "confidence" table: does the per-joint confidence (joint_confidence.h) tell the joints the
// tracker places well from those it cannot see (hidden by the body, beyond the image's
// edge)? A consumer that trusts confident joints and discounts the others needs the error to
// fall as the confidence rises.
//
// Every joint present in both skeletons (estimate confidence > 0, position finite) falls into
// one of kConfidenceBinCount bins by the estimate's confidence c:
//   [0, 0.25), [0.25, 0.5), [0.5, 0.75), [0.75, 1]
// Per bin: n (joint estimates), share (n over all estimates added), mean_cm (mean |estimate -
// truth|, cm) and gross_share (the share of the bin's estimates more than kGrossErrorM off).
// A bin without estimates reads n 0 and every figure 0.

#include <array>
#include <string_view>

#include "common/skeleton/skeleton.h"

namespace reenact::eval {

constexpr int kConfidenceBinCount = 4;
constexpr double kGrossErrorM = 0.10;

struct ConfidenceBinStats {
  int n = 0;
  double share = 0;
  double mean_cm = 0;
  double gross_share = 0;
};

class ConfidenceErrorTable {
 public:
  // Adds one frame; both skeletons in one frame (any).
  void Add(const Skeleton& estimate, const Skeleton& truth);
  std::array<ConfidenceBinStats, kConfidenceBinCount> Stats() const;

  // The bin of a confidence in [0, 1] (values outside are clamped into it, NaN to the lowest).
  static int Bin(double confidence);
  // The bin's range as printed: "0-0.25", "0.25-0.5", "0.5-0.75", "0.75-1".
  static std::string_view BinName(int bin);

 private:
  struct Sum {
    int n = 0, gross = 0;
    double error_m = 0;
  };
  std::array<Sum, kConfidenceBinCount> sums_{};
};

}  // namespace reenact::eval
