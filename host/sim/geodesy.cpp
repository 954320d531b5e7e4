// Latitude/longitude arithmetic; see trn/sim/geodesy.hpp.
#include "trn/sim/geodesy.hpp"

#include <cmath>
#include <cstdio>

#include "trn/error.hpp"

namespace trn::sim {
namespace {
constexpr double kDegPerRad = 57.29577951308232;

std::string degrees(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return buf;
}
}  // namespace

std::string geo_origin_problem(const GeoOrigin& o) {
    if (!(std::fabs(o.latitude_deg) <= kMaxOriginLatitudeDeg))
        return "latitude " + degrees(o.latitude_deg) + " deg is not within +-" + degrees(kMaxOriginLatitudeDeg) +
               " deg (the map's local projection degenerates towards the poles; latitudes run -90..90)";
    if (!(std::fabs(o.longitude_deg) <= 180)) return "longitude " + degrees(o.longitude_deg) + " deg is not within -180..180 deg";
    return "";
}

void check_geo_origin(const GeoOrigin& o, const std::string& what) {
    if (const std::string why = geo_origin_problem(o); !why.empty()) throw Error(what + ": " + why);
}

double wrap_longitude(double lon) {
    if (!std::isfinite(lon)) return lon;
    double w = std::fmod(lon + 180.0, 360.0);
    if (w < 0) w += 360.0;
    return w - 180.0;
}

std::array<double, 2> latlon_to_local_m(const GeoOrigin& o, double lat, double lon) {
    const double south = (o.latitude_deg - lat) / kDegPerRad * kEarthRadiusM;
    const double east = wrap_longitude(lon - o.longitude_deg) / kDegPerRad * kEarthRadiusM * std::cos(o.latitude_deg / kDegPerRad);
    return {east, south};
}

LatLon local_m_to_latlon(const GeoOrigin& o, double east_m, double south_m) {
    const double lat = o.latitude_deg - south_m / kEarthRadiusM * kDegPerRad;
    const double lon = o.longitude_deg + east_m / (kEarthRadiusM * std::cos(o.latitude_deg / kDegPerRad)) * kDegPerRad;
    return {lat, wrap_longitude(lon)};
}

}  // namespace trn::sim
