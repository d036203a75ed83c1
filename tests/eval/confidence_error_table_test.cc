// The confidence breakdown of `reenact-eval tracker` against constructed skeletons.
#include "tests/eval/confidence_error_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace reenact::eval {
namespace {

// Every joint present at (j, 0, 0) metres with confidence 1.
Skeleton Truth() {
  Skeleton s;
  for (int j = 0; j < kJointCount; ++j) s.Set(static_cast<Joint>(j), Eigen::Vector3d(j, 0, 0));
  return s;
}

TEST(ConfidenceErrorTable, BinsSplitAtQuartersWithTheEdgeInTheUpperBin) {
  EXPECT_EQ(ConfidenceErrorTable::Bin(0.0), 0);
  EXPECT_EQ(ConfidenceErrorTable::Bin(0.2499), 0);
  EXPECT_EQ(ConfidenceErrorTable::Bin(0.25), 1);
  EXPECT_EQ(ConfidenceErrorTable::Bin(0.5), 2);
  EXPECT_EQ(ConfidenceErrorTable::Bin(0.75), 3);
  EXPECT_EQ(ConfidenceErrorTable::Bin(1.0), 3);
  EXPECT_EQ(ConfidenceErrorTable::Bin(-1.0), 0);
  EXPECT_EQ(ConfidenceErrorTable::Bin(2.0), 3);
  EXPECT_EQ(ConfidenceErrorTable::Bin(std::numeric_limits<double>::quiet_NaN()), 0);
  EXPECT_EQ(ConfidenceErrorTable::BinName(0), "0-0.25");
  EXPECT_EQ(ConfidenceErrorTable::BinName(3), "0.75-1");
}

TEST(ConfidenceErrorTable, ErrorsLandInTheBinOfTheirConfidence) {
  // Two frames. In each, 4 joints are reported at confidence 0.1 and 20 cm off (a part the
  // tracker cannot see), the other 12 at confidence 1 and 2 cm off.
  ConfidenceErrorTable table;
  const Skeleton truth = Truth();
  for (int frame = 0; frame < 2; ++frame) {
    Skeleton estimate = truth;
    for (int j = 0; j < kJointCount; ++j) {
      const Joint joint = static_cast<Joint>(j);
      const bool unseen = j < 4;
      estimate.Set(joint, truth[joint] + Eigen::Vector3d(0, unseen ? 0.20 : 0.02, 0),
                   unseen ? 0.1 : 1.0);
    }
    table.Add(estimate, truth);
  }
  const auto bins = table.Stats();
  EXPECT_EQ(bins[0].n, 8);
  EXPECT_DOUBLE_EQ(bins[0].share, 0.25);
  EXPECT_NEAR(bins[0].mean_cm, 20.0, 1e-9);
  EXPECT_DOUBLE_EQ(bins[0].gross_share, 1.0);
  EXPECT_EQ(bins[3].n, 24);
  EXPECT_DOUBLE_EQ(bins[3].share, 0.75);
  EXPECT_NEAR(bins[3].mean_cm, 2.0, 1e-9);
  EXPECT_DOUBLE_EQ(bins[3].gross_share, 0.0);
  for (int b : {1, 2}) {
    EXPECT_EQ(bins[b].n, 0);
    EXPECT_EQ(bins[b].share, 0.0);
    EXPECT_EQ(bins[b].mean_cm, 0.0);
  }
}

TEST(ConfidenceErrorTable, MissingOrNonFiniteJointsAreLeftOut) {
  const Skeleton truth = Truth();
  Skeleton estimate = truth;
  estimate.confidence[Index(Joint::kHead)] = 0;  // missing in the estimate
  estimate[Joint::kNeck] = Eigen::Vector3d(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  Skeleton partial_truth = truth;
  partial_truth.confidence[Index(Joint::kLeftHand)] = 0;  // missing in the truth
  ConfidenceErrorTable table;
  table.Add(estimate, partial_truth);
  const auto bins = table.Stats();
  EXPECT_EQ(bins[3].n, kJointCount - 3);
  EXPECT_DOUBLE_EQ(bins[3].share, 1.0);
  EXPECT_EQ(bins[3].mean_cm, 0.0);
}

TEST(ConfidenceErrorTable, AnEmptyTableReadsZero) {
  const auto bins = ConfidenceErrorTable().Stats();
  for (const ConfidenceBinStats& b : bins) {
    EXPECT_EQ(b.n, 0);
    EXPECT_EQ(b.share, 0.0);
    EXPECT_EQ(b.mean_cm, 0.0);
    EXPECT_EQ(b.gross_share, 0.0);
  }
}

}  // namespace
}  // namespace reenact::eval
