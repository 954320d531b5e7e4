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
    // What OpenCV's decoder takes to read it as 8-bit grey, with the GrayImage copy: bytes per
    // pixel (2 for 8-bit formats, 16 for Radiance HDR's float RGB buffer ...) plus a fixed part
    // (a TIFF strip or tile buffer, a WebP file read whole).
    double decode_bytes_per_pixel = 2;
    std::uint64_t decode_extra_bytes = 0;
    const char* format = "";  // "PNG", "Radiance HDR", ...
    // What the no-data reader (load_validity) decodes at full depth, from the header where it says
    // (PNG, JPEG, TIFF); otherwise the most it may be (4 channels of 16 bits, alpha possible).
    int channels = 4, bits_per_sample = 16;
    bool alpha_possible = true;  // an alpha channel or PNG transparency (tRNS): a mask to read
    bool interlaced = false;     // an Adam7 PNG: its mask's decode holds every row at once
};

// Bytes load_validity's decode of such an image takes: a PNG's mask and one 8-bit RGBA row (every
// row when interlaced); another format's decoded pixels, their high bytes when 16-bit, and the mask.
double validity_decode_bytes(const ImageSize& size);

// Most bytes decoding one image file may take (2 GiB: a 2^30-pixel 8-bit map at 2 B/px), whatever
// its format: a 32768x32768 Radiance HDR (12 B/px of floats) is refused before OpenCV sees it.
inline constexpr double kMaxImageDecodeBytes = double(std::int64_t(1) << 31);

// Width and height as the header of a PNG, JPEG, BMP, PNM (P1-P6), PAM (P7), PFM, Radiance HDR,
// TIFF, WebP, JPEG 2000 or Sun raster file states them; nullopt for other formats or a header
// this reader does not understand. Throws trn::Error naming the file when it cannot be opened
// or is not a regular file.
std::optional<ImageSize> read_image_size(const std::string& path);

// Everything load_gray checks before OpenCV opens the file: a regular file (not a FIFO or device)
// of at most io::kMaxImageFileBytes, in a format whose header read_image_size reads, whose sides,
// pixels and decode cost are within trn/limits.hpp and kMaxImageDecodeBytes. Throws trn::Error
// naming the file; returns the header's size.
ImageSize check_image_file(const std::string& path);

}  // namespace trn
TRN_API_END
