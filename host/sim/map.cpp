#include "trn/sim/map.hpp"

#include <cmath>

#include "trn/error.hpp"
#include "trn/detail/angles.hpp"
#include "trn/sim/geodesy.hpp"

namespace trn::sim {

Map load_map(const std::string& path, double metres_per_pixel, std::optional<GeoOrigin> origin, std::optional<int> nodata) {
    if (!(metres_per_pixel > 0) || !std::isfinite(metres_per_pixel))
        throw Error(path + ": map resolution " + std::to_string(metres_per_pixel) + " m/px must be > 0");
    Map map;
    map.image = load_gray(path);
    map.valid = load_validity(path, nodata);
    map.metres_per_pixel = metres_per_pixel;
    map.origin = origin;
    return map;
}

LatLon map_pixel_to_latlon(const Map& map, double x, double y) {
    return local_m_to_latlon(map.origin.value_or(GeoOrigin{}), x * map.metres_per_pixel, y * map.metres_per_pixel);
}

}  // namespace trn::sim
