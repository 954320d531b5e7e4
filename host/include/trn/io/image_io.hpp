#pragma once
// Image files in and out (OpenCV underneath). Every failure throws trn::Error naming the file.
#include <cstdint>
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
void save_gray(const std::string& path, GrayView image);
// Writes a signed gradient as 8-bit PNG: 128 + g/8 clamped, so zero is mid-grey.
void save_gradient(const std::string& path, ImageView<const std::int16_t> g);

}  // namespace trn
TRN_API_END
