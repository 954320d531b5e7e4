#pragma once
// Decoding and encoding of image files behind trn/io/image_io.hpp. Two implementations with the same
// two functions: OpenCV's imgcodecs (image_codec_opencv.cpp, every format OpenCV reads; the normal
// build) and libpng (image_codec_png.cpp, PNG only; the device kit's libtrnkit_io, which must not
// pull in imgcodecs and its ~140 libraries). Both report failures as trn::Error naming the file.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "trn/io/image_io.hpp"

namespace trn::io::detail {

// Decodes the file as 8-bit grey (colour with ITU-R 601 weights, alpha dropped, 16-bit to its high
// byte), as cv::imread(path, IMREAD_GRAYSCALE) does. The size the header states is already checked.
GrayImage decode_gray(const std::string& path);

// The validity of load_validity (image_io.hpp) for a file that is not PNG (PNG masks are streamed by
// decode_png_validity, png_reader.hpp, in every build): 255 valid, 0 where alpha is 0 or every colour
// channel equals *nodata; empty when the file has no alpha and nodata is not given.
GrayImage decode_validity(const std::string& path, std::optional<int> nodata);

// Encodes in the format of the extension (".png", ...) into memory.
std::vector<std::uint8_t> encode_gray(const std::string& path, const std::string& extension, GrayView image);

// What this build reads and writes, for messages and `trnkit --version`-like reports.
const char* image_codec_name();

}  // namespace trn::io::detail
