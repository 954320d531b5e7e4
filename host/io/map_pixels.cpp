// A map's pixels and no-data, one way for every command; see trn/io/map_pixels.hpp.
#include "trn/io/map_pixels.hpp"

#include "trn/io/geotiff.hpp"

namespace trn::io {

MapPixels load_map_pixels(const std::string& path, std::optional<int> nodata) {
    if (has_geotiff_extension(path)) {
        GeoTiff g = read_geotiff(path, nodata);
        return {std::move(g.image), std::move(g.valid)};
    }
    GrayImage image = load_gray(path);
    return {std::move(image), load_validity(path, nodata)};
}

}  // namespace trn::io
