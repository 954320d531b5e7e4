#pragma once
// A map's pixels and its no-data, read one way by every command (issue 45): score, register and
// localize all honour the same sources of no-data. A GeoTIFF (a name ending .tif/.tiff, as localize
// reads it) through read_geotiff: GDAL's mask of band 1 (an alpha band, the nodata value, an
// internal mask band) and `nodata`; any other image through load_gray and load_validity: an alpha
// channel, a grey PNG's transparency (tRNS) and `nodata`.
#include <optional>
#include <string>

#include "trn/export.hpp"
#include "trn/io/image_io.hpp"

TRN_API_BEGIN
namespace trn::io {

struct MapPixels {
    GrayImage image;
    GrayImage valid;  // 255 valid, 0 not; empty: every pixel is valid
};

// Throws trn::Error naming the file (a GeoTIFF in a build without GDAL, or without a georeference,
// is refused as localize refuses it).
MapPixels load_map_pixels(const std::string& path, std::optional<int> nodata);

}  // namespace trn::io
TRN_API_END
