#pragma once
// Georeferenced orthophotos (GeoTIFF) read through GDAL: the raster as grey, its ground resolution
// from the geotransform, and latitude / longitude of map pixels through the file's CRS (PROJ, via
// OGRCoordinateTransformation). Only north-up maps in a projected CRS with square pixels are
// accepted; anything else is refused naming the file and what to do. GDAL is optional at build
// time: without it every call here throws a trn::Error saying so (geotiff_supported() is false).
// Map pixel (x, y) is the centre of pixel column x, row y, as everywhere in trnkit (trn::sim::Map);
// in GDAL's pixel/line space that point is (x + 0.5, y + 0.5).
#include <array>
#include <optional>
#include <memory>
#include <string>

#include "trn/io/image_io.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::io {

// This build can read GeoTIFF (it was built with GDAL).
bool geotiff_supported();
// The name ends in .tif or .tiff (any case): such a map is read as a GeoTIFF.
bool has_geotiff_extension(const std::string& path);

struct GeoTiff {
    GrayImage image;                       // band 1, or RGB(A) converted to grey (ITU-R 601, as load_gray)
    double metres_per_pixel = 0;           // geotransform pixel size times the CRS's linear unit
    std::array<double, 6> geotransform{};  // GDAL's: X = gt0 + col*gt1 + row*gt2, Y = gt3 + col*gt4 + row*gt5
    std::string crs_name;                  // e.g. "WGS 84 / UTM zone 32N"
    std::string crs_wkt;
    // No-data: 255 valid, 0 not, from GDAL's mask of band 1 (an alpha band, a nodata value or an
    // internal mask band) and, with `nodata`, pixels whose every colour band equals it. Empty: all valid.
    GrayImage valid;
};
GeoTiff read_geotiff(const std::string& path, std::optional<int> nodata = std::nullopt);

struct GeoPoint {
    double latitude_deg = 0, longitude_deg = 0;  // WGS84
};

// Map pixel <-> WGS84 latitude / longitude for one GeoTIFF.
class GeoReference {
public:
    explicit GeoReference(const GeoTiff& map, const std::string& source);
    ~GeoReference();
    GeoReference(GeoReference&&) noexcept;
    GeoReference& operator=(GeoReference&&) noexcept;
    GeoPoint to_latlon(double x, double y) const;
    // Map pixel (x, y) of a latitude / longitude.
    std::array<double, 2> to_pixel(double latitude_deg, double longitude_deg) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace trn::io
TRN_API_END
