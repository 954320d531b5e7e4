// The parts of trn/io/geotiff.hpp that do not need GDAL.
#include <algorithm>
#include <cctype>
#include <filesystem>

#include "trn/io/geotiff.hpp"

namespace trn::io {

bool has_geotiff_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".tif" || ext == ".tiff";
}

}  // namespace trn::io
