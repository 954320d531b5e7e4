#pragma once
// Image files in and out (OpenCV underneath). Every failure throws trn::Error naming the file.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "trn/image.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn {

// An owning 8-bit grey image.
struct GrayImage {
    int width = 0, height = 0;
    std::vector<std::uint8_t> pixels;  // row-major, stride == width
    GrayView view() const { return {pixels.data(), width, height, width}; }
};

// Reads any format OpenCV reads and converts colour to grey (ITU-R 601 weights, as cv::cvtColor).
GrayImage load_gray(const std::string& path);
// The no-data of an image file as load_gray's pixels see it: 255 where a pixel is valid, 0 where
// its alpha is 0 or (when `nodata` is given, 0..255) every colour channel equals *nodata, as
// orthomosaic tools write no-data. Empty (width 0) when the file has no alpha channel and `nodata`
// is not given: every pixel is valid. 16-bit files are compared by their high byte, as load_gray reads them.
GrayImage load_validity(const std::string& path, std::optional<int> nodata = std::nullopt);
// load_validity's result as Backend::upload_map takes it: an empty view when every pixel is valid.
inline GrayView validity_view(const GrayImage& valid) { return valid.width > 0 ? valid.view() : GrayView{}; }
void save_gray(const std::string& path, GrayView image);
// Writes a signed gradient as 8-bit PNG: 128 + g/8 clamped, so zero is mid-grey.
void save_gradient(const std::string& path, ImageView<const std::int16_t> g);

}  // namespace trn
TRN_API_END
