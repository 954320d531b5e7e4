// trn/io/geotiff.hpp in a build without GDAL: every call says so, naming the file.
#include "trn/error.hpp"
#include "trn/io/geotiff.hpp"

namespace trn::io {
namespace {
[[noreturn]] void no_gdal(const std::string& path) {
    throw Error(path + ": GeoTIFF maps are read with GDAL, and this build of trnkit has none (install libgdal-dev, "
                       "scripts/install-deps.sh, and rebuild; or give a PNG map and its metres per pixel)");
}
}  // namespace

bool geotiff_supported() { return false; }
GeoTiff read_geotiff(const std::string& path, std::optional<int>) { no_gdal(path); }

struct GeoReference::Impl {};
GeoReference::GeoReference(const GeoTiff&, const std::string& source) { no_gdal(source); }
GeoReference::~GeoReference() = default;
GeoReference::GeoReference(GeoReference&&) noexcept = default;
GeoReference& GeoReference::operator=(GeoReference&&) noexcept = default;
GeoPoint GeoReference::to_latlon(double, double) const { return {}; }
std::array<double, 2> GeoReference::to_pixel(double, double) const { return {}; }

}  // namespace trn::io
