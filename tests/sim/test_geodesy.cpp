// The one home of latitude/longitude arithmetic (trn/sim/geodesy.hpp, issue 45 class 6): an
// origin at a pole is refused (--map-origin 90,180 gave longitudes of 6e13 degrees), longitudes
// wrap at the antimeridian (fixes 1 m apart across it were 40 075 km apart), the projection
// round-trips.
#include <gtest/gtest.h>

#include <cmath>

#include "trn/error.hpp"
#include "trn/sim/geodesy.hpp"
#include "trn/sim/map.hpp"

namespace trn::sim {
namespace {

TEST(Geodesy, LongitudesWrapIntoMinus180To180) {
    EXPECT_DOUBLE_EQ(wrap_longitude(190), -170);
    EXPECT_DOUBLE_EQ(wrap_longitude(-190), 170);
    EXPECT_DOUBLE_EQ(wrap_longitude(180), -180);
    EXPECT_DOUBLE_EQ(wrap_longitude(-180), -180);
    EXPECT_DOUBLE_EQ(wrap_longitude(540), -180);
    EXPECT_DOUBLE_EQ(wrap_longitude(12.5), 12.5);
    EXPECT_TRUE(std::isnan(wrap_longitude(NAN)));
}

TEST(Geodesy, DistancesAcrossTheAntimeridianAreShort) {
    const GeoOrigin o{-17.0, 179.99999};  // Fiji
    const auto [east, south] = latlon_to_local_m(o, -17.0, -179.99999);  // 0.00002 deg east of it
    EXPECT_NEAR(east, 0.00002 / 57.29577951308232 * kEarthRadiusM * std::cos(17.0 / 57.29577951308232), 1e-6);
    EXPECT_LT(east, 3.0);
    EXPECT_NEAR(south, 0, 1e-9);
    const auto [west, s2] = latlon_to_local_m(GeoOrigin{-17.0, -179.99999}, -17.0, 179.99999);
    EXPECT_NEAR(west, -east, 1e-6);
    (void)s2;
}

TEST(Geodesy, MapPixelsEastOfTheAntimeridianHaveWrappedLongitudes) {
    Map map;
    map.metres_per_pixel = 1;
    map.origin = GeoOrigin{-17.0, 179.9995};
    const LatLon p = map_pixel_to_latlon(map, 200, 0);  // ~0.0019 deg east: past 180
    EXPECT_GE(p.longitude_deg, -180);
    EXPECT_LT(p.longitude_deg, -179.99);
    const auto back = latlon_to_local_m(*map.origin, p.latitude_deg, p.longitude_deg);
    EXPECT_NEAR(back[0], 200, 1e-6);
    EXPECT_NEAR(back[1], 0, 1e-6);
}

TEST(Geodesy, AnOriginAtAPoleIsRefused) {
    EXPECT_EQ(geo_origin_problem({85, 180}), "");
    EXPECT_EQ(geo_origin_problem({-85, -180}), "");
    EXPECT_NE(geo_origin_problem({90, 180}).find("latitude 90 deg is not within +-85 deg"), std::string::npos);
    EXPECT_NE(geo_origin_problem({-89.5, 0}).find("latitude -89.5 deg"), std::string::npos);
    EXPECT_NE(geo_origin_problem({NAN, 0}).find("latitude nan"), std::string::npos);
    EXPECT_NE(geo_origin_problem({0, 180.5}).find("longitude 180.5 deg is not within -180..180"), std::string::npos);
    EXPECT_THROW(check_geo_origin({90, 180}, "flight.json: origin"), Error);
}

}  // namespace
}  // namespace trn::sim
