#pragma once
// A map for the simulator and the particle filter: an 8-bit grey orthophoto, its ground resolution
// and, optionally, the geographic position of its top-left pixel centre. Map pixel x grows to the
// east, y to the south (north is up), as in every image.
#include <optional>
#include <string>

#include "trn/io/image_io.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::sim {

struct GeoOrigin {
    double latitude_deg = 0;   // of map pixel (0, 0)
    double longitude_deg = 0;
};

struct Map {
    GrayImage image;
    GrayImage valid;  // no-data: 255 valid, 0 not (image's size); empty: every pixel is valid
    double metres_per_pixel = 1.0;
    std::optional<GeoOrigin> origin;

    // The no-data mask as Backend::upload_map takes it (an empty view when every pixel is valid).
    GrayView valid_view() const { return validity_view(valid); }
    double width_m() const { return image.width * metres_per_pixel; }
    double height_m() const { return image.height * metres_per_pixel; }
};

// Any image OpenCV reads (colour is converted to grey), its no-data from the alpha channel and
// `nodata` (trn::load_validity). Throws trn::Error naming the file or the bad resolution.
Map load_map(const std::string& path, double metres_per_pixel, std::optional<GeoOrigin> origin = std::nullopt,
             std::optional<int> nodata = std::nullopt);

// Latitude / longitude of a map pixel: local equirectangular projection around the origin
// (good to centimetres over the few kilometres a map covers). A map without origin uses (0, 0).
struct LatLon {
    double latitude_deg = 0, longitude_deg = 0;
};
LatLon map_pixel_to_latlon(const Map& map, double x, double y);

}  // namespace trn::sim
TRN_API_END
