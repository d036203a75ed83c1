#include "server/geo/geodesic.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "common/error/check.h"

namespace reenact::server {
namespace {

// Hand values: arc length R * angle, R = 6371008.8 m.
TEST(Haversine, MatchesArcLengthsAlongGreatCircles) {
  EXPECT_NEAR(HaversineDistanceM(0, 0, 0, 1), 111195.0802, 1e-3);
  EXPECT_NEAR(HaversineDistanceM(0, 0, 90, 0), 10007557.2210, 1e-3);
  EXPECT_NEAR(HaversineDistanceM(0, 179.5, 0, -179.5), 111195.0802, 1e-3);
  EXPECT_NEAR(HaversineDistanceM(89.9, 0, 89.9, 180), 22239.0160, 1e-3);
  EXPECT_NEAR(HaversineDistanceM(90, 0, 90, 123), 0.0, 1e-6);
  EXPECT_NEAR(HaversineDistanceM(0, 0, 0, 180), std::numbers::pi * kEarthMeanRadiusM, 1e-3);
}

// A point at distance d and bearing b from (lat, lon), by the spherical direct formula.
std::pair<double, double> Destination(double lat_deg, double lon_deg, double bearing_deg,
                                      double d_m) {
  const double k = std::numbers::pi / 180;
  const double lat = lat_deg * k, lon = lon_deg * k, b = bearing_deg * k;
  const double a = d_m / kEarthMeanRadiusM;
  const double lat2 = std::asin(std::sin(lat) * std::cos(a) + std::cos(lat) * std::sin(a) * std::cos(b));
  double lon2 = lon + std::atan2(std::sin(b) * std::sin(a) * std::cos(lat),
                                 std::cos(a) - std::sin(lat) * std::sin(lat2));
  lon2 = std::remainder(lon2, 2 * std::numbers::pi);
  return {lat2 / k, lon2 / k};
}

bool Covered(const std::vector<LatLonBox>& boxes, double lat, double lon) {
  for (const auto& b : boxes) {
    if (lat >= b.min_lat_deg && lat <= b.max_lat_deg && lon >= b.min_lon_deg &&
        lon <= b.max_lon_deg) {
      return true;
    }
  }
  return false;
}

TEST(BoundingBoxes, CoverEveryPointOfTheCircle) {
  const double centers[][2] = {{0, 0}, {45, 10}, {-60, 179.9}, {10, -179.99}, {89.99, 30},
                               {-89.5, -100}, {70, 179}};
  for (const auto& c : centers) {
    for (double radius : {0.0, 10.0, 5000.0, 200000.0}) {
      const auto boxes = BoundingBoxes(c[0], c[1], radius);
      for (int bearing = 0; bearing < 360; bearing += 5) {
        for (double fraction : {0.5, 1.0}) {
          const auto [lat, lon] = Destination(c[0], c[1], bearing, radius * fraction);
          EXPECT_TRUE(Covered(boxes, lat, lon))
              << c[0] << "," << c[1] << " r=" << radius << " bearing=" << bearing;
        }
      }
    }
  }
}

TEST(BoundingBoxes, SplitsAtTheAntimeridianAndWidensAtThePoles) {
  EXPECT_EQ(BoundingBoxes(0, 179.99, 5000).size(), 2u);
  EXPECT_EQ(BoundingBoxes(0, 0, 5000).size(), 1u);
  const auto polar = BoundingBoxes(89.99, 0, 5000);
  ASSERT_EQ(polar.size(), 1u);
  EXPECT_EQ(polar[0].min_lon_deg, -180.0);
  EXPECT_EQ(polar[0].max_lon_deg, 180.0);
  EXPECT_EQ(polar[0].max_lat_deg, 90.0);
}

TEST(BoundingBoxes, RejectsInvalidInput) {
  EXPECT_THROW(BoundingBoxes(91, 0, 1), CheckError);
  EXPECT_THROW(BoundingBoxes(0, 0, -1), CheckError);
}

}  // namespace
}  // namespace reenact::server
