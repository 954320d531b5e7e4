#pragma once
// The one home of latitude/longitude arithmetic (issue 45): ranges, the longitude wrap at the
// antimeridian, and the local projection a map's origin defines. Every conversion between a map
// pixel and latitude/longitude that uses an origin (flight.json's, import-photos --map-origin),
// and so every error against GPS computed through it, goes through here.
//
// The projection is local equirectangular around the origin (good to centimetres over the few
// kilometres a map covers): east = R cos(lat0) dlon, south = R (lat0 - lat). It degenerates at the
// poles (cos(90 deg) = 0 made --map-origin 90,180 give longitudes of 6e13 degrees), so an origin
// must lie within kMaxOriginLatitudeDeg of the equator. Longitude differences are wrapped into
// [-180, 180): two fixes 1 m apart across the antimeridian are 1 m apart, not 40 075 km.
#include <array>
#include <string>

#include "trn/export.hpp"
#include "trn/sim/map.hpp"

TRN_API_BEGIN
namespace trn::sim {

inline constexpr double kEarthRadiusM = 6378137.0;  // WGS 84 equatorial radius
inline constexpr double kMaxOriginLatitudeDeg = 85.0;

// Why `origin` cannot be a map's origin ("latitude 90 deg is not within +-85 deg ..."), "" when it
// can: latitude finite and within +-kMaxOriginLatitudeDeg, longitude finite and within [-180, 180].
std::string geo_origin_problem(const GeoOrigin& origin);
// Throws trn::Error "WHAT: <the problem>" when there is one.
void check_geo_origin(const GeoOrigin& origin, const std::string& what);

// `lon` in [-180, 180) (a finite value; NaN stays NaN).
double wrap_longitude(double lon);

// Metres east and south of the origin (the longitude difference wrapped first).
std::array<double, 2> latlon_to_local_m(const GeoOrigin& origin, double lat, double lon);

// The inverse: latitude and longitude (wrapped into [-180, 180)) of a point east/south of the origin.
LatLon local_m_to_latlon(const GeoOrigin& origin, double east_m, double south_m);

}  // namespace trn::sim
TRN_API_END
