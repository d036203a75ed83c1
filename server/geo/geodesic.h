#pragma once
// Great-circle geometry on a spherical Earth for nearby search. Angles in degrees (WGS84
// latitude in [-90, 90], longitude in [-180, 180]), distances in metres. The sphere has the
// IUGG mean radius; against the WGS84 ellipsoid the haversine distance errs by < 0.5 %,
// ample for "clips near me".

#include <vector>

namespace reenact::server {

inline constexpr double kEarthMeanRadiusM = 6371008.8;

// Great-circle distance by the haversine formula:
//   a = sin^2(dlat/2) + cos(lat1) cos(lat2) sin^2(dlon/2),  d = 2 R asin(sqrt(a)).
// Exact for antipodes and across the antimeridian (dlon is used through sin^2 only).
double HaversineDistanceM(double lat1_deg, double lon1_deg, double lat2_deg, double lon2_deg);

// An axis-aligned box in degrees, min <= max on both axes (never wrapping).
struct LatLonBox {
  double min_lat_deg = 0.0;
  double max_lat_deg = 0.0;
  double min_lon_deg = 0.0;
  double max_lon_deg = 0.0;
};

// Boxes that together cover every point within radius_m of (lat, lon): one box normally,
// two when the circle crosses the antimeridian, and one full-longitude band when it reaches a
// pole. The longitude half-width is asin(sin(d) / cos(lat)) for angular radius d, the
// exact extent of a spherical cap. Precondition: valid coordinates, radius_m >= 0.
std::vector<LatLonBox> BoundingBoxes(double lat_deg, double lon_deg, double radius_m);

}  // namespace reenact::server
