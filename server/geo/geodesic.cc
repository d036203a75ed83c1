#include "server/geo/geodesic.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/error/check.h"

namespace reenact::server {

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kRadToDeg = 180.0 / std::numbers::pi;

}  // namespace

double HaversineDistanceM(double lat1_deg, double lon1_deg, double lat2_deg, double lon2_deg) {
  const double lat1 = lat1_deg * kDegToRad;
  const double lat2 = lat2_deg * kDegToRad;
  const double half_dlat = 0.5 * (lat2 - lat1);
  const double half_dlon = 0.5 * (lon2_deg - lon1_deg) * kDegToRad;
  const double s_lat = std::sin(half_dlat);
  const double s_lon = std::sin(half_dlon);
  const double a = std::clamp(s_lat * s_lat + std::cos(lat1) * std::cos(lat2) * s_lon * s_lon,
                              0.0, 1.0);
  return 2.0 * kEarthMeanRadiusM * std::asin(std::sqrt(a));
}

std::vector<LatLonBox> BoundingBoxes(double lat_deg, double lon_deg, double radius_m) {
  REENACT_CHECK(lat_deg >= -90.0 && lat_deg <= 90.0, "latitude out of range");
  REENACT_CHECK(lon_deg >= -180.0 && lon_deg <= 180.0, "longitude out of range");
  REENACT_CHECK(radius_m >= 0.0, "radius must be >= 0");
  // A hair of slack so rounding never drops a point lying exactly on the circle.
  const double angular = radius_m / kEarthMeanRadiusM + 1e-12;
  const double angular_deg = angular * kRadToDeg;
  const double min_lat = lat_deg - angular_deg;
  const double max_lat = lat_deg + angular_deg;
  if (min_lat <= -90.0 || max_lat >= 90.0 || angular >= std::numbers::pi / 2) {
    return {{std::max(min_lat, -90.0), std::min(max_lat, 90.0), -180.0, 180.0}};
  }
  const double ratio = std::sin(angular) / std::cos(lat_deg * kDegToRad);
  if (ratio >= 1.0) return {{min_lat, max_lat, -180.0, 180.0}};
  const double half_width_deg = std::asin(ratio) * kRadToDeg;
  const double min_lon = lon_deg - half_width_deg;
  const double max_lon = lon_deg + half_width_deg;
  if (min_lon < -180.0) {
    return {{min_lat, max_lat, -180.0, max_lon}, {min_lat, max_lat, min_lon + 360.0, 180.0}};
  }
  if (max_lon > 180.0) {
    return {{min_lat, max_lat, min_lon, 180.0}, {min_lat, max_lat, -180.0, max_lon - 360.0}};
  }
  return {{min_lat, max_lat, min_lon, max_lon}};
}

}  // namespace reenact::server
