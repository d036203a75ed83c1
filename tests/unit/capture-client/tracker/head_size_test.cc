// The head's size from a person's depth points (head_size.h) on ray-cast scenes of known
// geometry, its degenerate inputs, and the proportional body's head scaled by it
// (body_calibration.h's WithHeadScaled and ProportionalBody).
#include "capture-client/tracker/head_size.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "capture-client/tracker/body_calibration.h"
#include "common/error/check.h"
#include "tests/unit/capture-client/tracker/capsule_body_scene.h"

namespace reenact::capture {
namespace {

using tracker_test::AboveFloor;
using tracker_test::SceneBlob;
using Capsule = tracker_test::SceneCapsule;

// A figure at depth z standing on the floor, facing the sensor: a head (a sphere of radius
// r, its top at 1.75 m), a neck (radius 0.45 r, from the chin 8 cm down) and a trunk (a
// capsule of radius 0.17, its top 2 cm below the neck's bottom, wider than any head here).
std::vector<Capsule> Figure(double r, double z = 3) {
  const double top = 1.75, chin = top - 2 * r, neck_bottom = chin - 0.08;
  return {{AboveFloor(0, top - r, z), AboveFloor(0, top - r, z), r},
          {AboveFloor(0, chin + 0.2 * r, z), AboveFloor(0, neck_bottom, z), 0.45 * r},
          {AboveFloor(0, neck_bottom - 0.02 - 0.17, z), AboveFloor(0, 0.5, z), 0.17}};
}

const double kFy = PinholeCamera::KinectLike().fy;
// The slice height at 3 m: two grid rows of 2 px, 2.3 cm; a grid column is half that.
const double kSlice = 2 * 2 * 3.0 / kFy;

TEST(HeadSize, ASphereHeadGivesItsRadiusAndItsNeck) {
  for (const double r : {0.09, 0.13}) {
    const auto head = MeasureHeadSize(SceneBlob(Figure(r)), kFy);
    ASSERT_TRUE(head) << r;
    // The widest slice holds the equator; its outermost grid columns lie within one column
    // (1.2 cm) inside the outline on either side.
    EXPECT_LE(head->half_width_m, r + 1e-3) << r;
    EXPECT_GT(head->half_width_m, r - 0.5 * kSlice) << r;
    // A sphere narrows below 0.85 of its width at 1.53 r below its top (head_size.h); the
    // slice that first lies wholly below that depth is reported by its middle, half a slice
    // lower, and the widest slice read short by up to two columns moves the threshold by
    // under a slice.
    const double neck = r * (1 + std::sqrt(1 - 0.85 * 0.85));
    EXPECT_GT(head->neck_below_top_m, neck - 0.5 * kSlice) << r;
    EXPECT_LT(head->neck_below_top_m, neck + 1.5 * kSlice) << r;
  }
}

TEST(HeadSize, TheNeckDepthGrowsWithTheHead) {
  // Two heads 9 and 13 cm in radius on the same body: the neck depths differ by about 1.53
  // times the 4 cm, give or take a slice.
  const auto small = MeasureHeadSize(SceneBlob(Figure(0.09)), kFy);
  const auto large = MeasureHeadSize(SceneBlob(Figure(0.13)), kFy);
  ASSERT_TRUE(small && large);
  EXPECT_NEAR(large->neck_below_top_m - small->neck_below_top_m, 1.53 * 0.04, kSlice);
}

TEST(HeadSize, ArmsRaisedAboveTheHeadHideTheNeck) {
  // Forearms held up either side of the head, 25 cm out, up to 2.0 m: every slice from the
  // hands down to the shoulders is as wide as the arms apart, so no slice narrows.
  std::vector<Capsule> figure = Figure(0.1);
  for (const double x : {-0.25, 0.25})
    figure.push_back({AboveFloor(x, 1.35, 3), AboveFloor(x, 2.0, 3), 0.05});
  EXPECT_FALSE(MeasureHeadSize(SceneBlob(figure), kFy));
}

TEST(HeadSize, AHeadCutByTheImagesEdgeGivesNoMeasurement) {
  // At 0.8 m the level sensor (1.3 m high, 255 px above the principal point at f = 516.5 px)
  // sees up to 1.3 + 0.8 * 255 / 516.5 = 1.69 m: the top of the 1.75 m head is cut, while the
  // chin and the neck (1.55 m and below) are in view. At 1.2 m it sees up to 1.89 m.
  EXPECT_FALSE(MeasureHeadSize(SceneBlob(Figure(0.1, 0.8)), kFy));
  EXPECT_TRUE(MeasureHeadSize(SceneBlob(Figure(0.1, 1.2)), kFy));
}

TEST(HeadSize, DegenerateBlobsGiveNoMeasurement) {
  const PersonBlob good = SceneBlob(Figure(0.1));
  ASSERT_TRUE(MeasureHeadSize(good, kFy));
  PersonBlob no_floor = good;
  no_floor.floor_in_sensor.reset();
  EXPECT_FALSE(MeasureHeadSize(no_floor, kFy));
  PersonBlob no_person = good;
  no_person.status = DetectStatus::kNoPerson;
  EXPECT_FALSE(MeasureHeadSize(no_person, kFy));
  PersonBlob empty = good;
  empty.points.clear();
  EXPECT_FALSE(MeasureHeadSize(empty, kFy));
  // Up along the line of sight (a sensor looking straight down on the head): no horizontal
  // direction across it.
  PersonBlob straight_down;
  straight_down.status = DetectStatus::kOk;
  straight_down.grid_step_px = 2;
  straight_down.floor_in_sensor = Plane3{Eigen::Vector3d(0, 0, -1), -3.0};
  for (int i = -5; i <= 5; ++i)
    for (int j = -5; j <= 5; ++j)
      straight_down.points.emplace_back(0.01 * i, 0.01 * j, 1.2 + 1e-3 * (i * i + j * j));
  EXPECT_FALSE(MeasureHeadSize(straight_down, kFy));
  EXPECT_THROW(MeasureHeadSize(good, 0.0), CheckError);
  EXPECT_THROW(MeasureHeadSize(good, kFy, HeadSizeOptions{.neck_ratio = 1.0}), CheckError);
}

TEST(HeadSize, ScalingTheHeadKeepsTheStandingHeightAndTheLegs) {
  const BodyShape average = BodyShape::FromHeight(1.7);
  const BodyShape large = WithHeadScaled(average, 1.4);
  EXPECT_NEAR(large.head_radius, 1.4 * average.head_radius, 1e-12);
  EXPECT_NEAR(large.head_rise, 1.4 * average.head_rise, 1e-12);
  EXPECT_NEAR(large.StandingHeight(), average.StandingHeight(), 1e-12);
  EXPECT_EQ(large.thigh, average.thigh);
  EXPECT_EQ(large.shin, average.shin);
  // The neck lies lower by the head's growth, taken from the spine in proportion.
  const double growth = 0.4 * (average.head_radius + average.head_rise);
  EXPECT_NEAR(large.lower_spine + large.upper_spine,
              average.lower_spine + average.upper_spine - growth, 1e-12);
  EXPECT_NEAR(large.lower_spine / large.upper_spine, average.lower_spine / average.upper_spine,
              1e-12);
  EXPECT_THROW(WithHeadScaled(average, 0.0), CheckError);
  EXPECT_THROW(WithHeadScaled(average, std::nan("")), CheckError);
}

TEST(HeadSize, TheProportionalBodysHeadFollowsTheMeasuredNeckDepth) {
  PersonBlob blob = SceneBlob(Figure(0.1));
  blob.top_height_m = 1.75;
  const CalibrationOptions options;  // average depth 0.108 H, noise 0.15, scale in [0.75, 1.7]
  const BodyShape average = BodyShape::FromHeight(1.75);
  const double average_depth = 0.108 * 1.75;
  const auto head_scale = [&](double depth) {
    const BodyCalibration c = ProportionalBody(blob, options, depth);
    EXPECT_EQ(c.status, CalibrationStatus::kOk);
    EXPECT_NEAR(c.shape.StandingHeight(), 1.75, 1e-9);
    EXPECT_NEAR(c.radius_ratio[0], c.shape.PartRadii()[0] / c.shape.PartLengths()[0], 1e-12);
    return c.shape.head_radius / average.head_radius;
  };
  // Without a measurement, at the average depth and within the noise of it: the average head.
  EXPECT_EQ(ProportionalBody(blob, options).shape.head_radius, average.head_radius);
  EXPECT_NEAR(head_scale(average_depth), 1.0, 1e-12);
  EXPECT_NEAR(head_scale(1.12 * average_depth), 1.0, 1e-12);
  EXPECT_NEAR(head_scale(0.88 * average_depth), 1.0, 1e-12);
  // Beyond the noise, the excess: 1.4 times the average depth gives 1.25 times the head, 0.7
  // times gives 0.85; far beyond either way, the clamp.
  EXPECT_NEAR(head_scale(1.4 * average_depth), 1.25, 1e-12);
  EXPECT_NEAR(head_scale(0.7 * average_depth), 0.85, 1e-12);
  EXPECT_NEAR(head_scale(1.0), options.max_head_scale, 1e-12);
  EXPECT_NEAR(head_scale(0.01), options.min_head_scale, 1e-12);
  EXPECT_THROW(ProportionalBody(blob, options, 0.0), CheckError);
  EXPECT_THROW(ProportionalBody(blob, options, std::nan("")), CheckError);
}

}  // namespace
}  // namespace reenact::capture
