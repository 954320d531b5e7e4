#include "trn/io/image_io.hpp"

#include <filesystem>
#include <string_view>
#include <opencv2/core.hpp>

#include "image_codec.hpp"
#include "png_reader.hpp"

#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"
#include "trn/io/image_header.hpp"
#include "trn/io/input_file.hpp"
#include "trn/limits.hpp"

namespace trn {

GrayImage load_gray(const std::string& path) {
    // A regular file in a format whose header trnkit reads, its sides, pixels and decode cost
    // within the limits, before OpenCV allocates anything (image_header.hpp).
    check_image_file(path);
    const std::string what = path + ": image";
    GrayImage img = io::detail::decode_gray(path);
    limits::check_image(what, img.width, img.height, limits::kMaxMapPixels, limits::kLoadBytesPerPixel);
    return img;
}

GrayImage load_validity(const std::string& path, std::optional<int> nodata) {
    if (nodata && (*nodata < 0 || *nodata > 255))
        throw Error(path + ": no-data value " + std::to_string(*nodata) + " is not an 8-bit grey level (0..255)");
    const ImageSize size = check_image_file(path);
    // No alpha, no transparency and no value named: every pixel is valid; the map is not decoded again.
    if (!nodata && !size.alpha_possible) return {};
    // The mask's decode (PNG: streamed, the mask and a row; other formats at the file's full depth,
    // a 16-bit RGBA TIFF 8 B/px, their high bytes and the mask): the per-image budget holds for it
    // too, before any decoder runs.
    const double bytes = validity_decode_bytes(size);
    if (bytes > kMaxImageDecodeBytes)
        throw Error(io::quote_input(path, 512) + ": image " + std::to_string(size.width) + "x" + std::to_string(size.height) + " (" + size.format +
                    ", " + std::to_string(size.channels) + " channels of " + std::to_string(size.bits_per_sample) + " bits) needs ~" +
                    limits::format_bytes(bytes) + " to read its no-data mask (limit " + limits::format_bytes(kMaxImageDecodeBytes) + " per image)");
    limits::check_memory(path + ": no-data mask", bytes);
    GrayImage valid = std::string_view(size.format) == "PNG" ? io::detail::decode_png_validity(path, nodata, "")
                                                             : io::detail::decode_validity(path, nodata);
    if (valid.width > 0) limits::check_image(path + ": image", valid.width, valid.height, limits::kMaxMapPixels, limits::kLoadBytesPerPixel);
    return valid;
}

// Encoded in memory (format from the extension), then written whole: a full disk or a killed run
// never leaves a cut image under the final name.
void save_gray(const std::string& path, GrayView image) {
    const std::string ext = std::filesystem::path(path).extension().string();
    if (ext.empty()) throw Error(path + ": no image extension (.png, .jpg, .tif, ...)");
    const std::vector<std::uint8_t> bytes = io::detail::encode_gray(path, ext, image);
    io::write_file_atomic(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

void save_gradient(const std::string& path, ImageView<const std::int16_t> g) {
    const cv::Mat src(g.height, g.width, CV_16SC1, const_cast<std::int16_t*>(g.data), g.stride * sizeof(std::int16_t));
    cv::Mat out;
    src.convertTo(out, CV_8UC1, 1.0 / 8.0, 128.0);
    save_gray(path, {out.data, out.cols, out.rows, static_cast<std::ptrdiff_t>(out.step)});
}

}  // namespace trn
