#pragma once
// Image dimensions from a file's header, without decoding it, so that load_gray can refuse a
// too-large image before any pixel memory is allocated (OpenCV 4.6 has no public header-only read).
#include <cstdint>
#include <optional>
#include <string>
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn {

struct ImageSize {
    std::int64_t width = 0, height = 0;
};

// Width and height as the header of a PNG, JPEG, BMP, PNM (P1-P6) or TIFF file states them;
// nullopt for other formats or a header this reader does not understand (OpenCV then reports it).
// Throws trn::Error naming the file only when it cannot be opened.
std::optional<ImageSize> read_image_size(const std::string& path);

}  // namespace trn
TRN_API_END
