// Image files through libpng alone: PNG in and out, nothing else (the device kit's libtrnkit_io, see
// image_codec.hpp). Reads as OpenCV's PNG decoder does for IMREAD_GRAYSCALE (the same libpng
// transformations), so a grey or colour PNG gives the same pixels in both builds.
#include <png.h>

#include "image_codec.hpp"
#include "png_reader.hpp"
#include "trn/error.hpp"

namespace trn::io::detail {
namespace {

const std::string kNotPngHint = "; this build of trnkit reads PNG only (the device kit's image reader, "
                                "built without OpenCV imgcodecs): convert the image to PNG";

}  // namespace

GrayImage decode_gray(const std::string& path) {
    PngReader reader(path, kNotPngHint);
    png_structp png = reader.png;
    png_infop info = reader.info;
    GrayImage img;
    std::vector<png_bytep> rows;
    if (setjmp(reader.errors.jump)) throw Error(path + ": cannot decode PNG (" + reader.errors.message + ")");
    reader.start();
    const int color_type = png_get_color_type(png, info), bit_depth = png_get_bit_depth(png, info);
    if (bit_depth > 8) png_set_strip_16(png);
    png_set_strip_alpha(png);
    if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
    if ((color_type & PNG_COLOR_MASK_COLOR) == 0 && bit_depth < 8) png_set_expand_gray_1_2_4_to_8(png);
    if (color_type & PNG_COLOR_MASK_COLOR) png_set_rgb_to_gray(png, 1, 0.299, 0.587);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);

    img.width = static_cast<int>(png_get_image_width(png, info));
    img.height = static_cast<int>(png_get_image_height(png, info));
    if (png_get_rowbytes(png, info) != static_cast<std::size_t>(img.width)) png_error(png, "unexpected row layout after conversion to grey");
    img.pixels.resize(std::size_t(img.width) * img.height);
    rows.resize(img.height);
    for (int y = 0; y < img.height; ++y) rows[y] = img.pixels.data() + std::size_t(y) * img.width;
    png_read_image(png, rows.data());
    png_read_end(png, nullptr);
    return img;
}

GrayImage decode_validity(const std::string& path, std::optional<int> nodata) {
    return decode_png_validity(path, nodata, kNotPngHint);
}

namespace {
void append_bytes(png_structp png, png_bytep data, png_size_t length) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(png_get_io_ptr(png));
    out->insert(out->end(), data, data + length);
}
void no_flush(png_structp) {}
}  // namespace

std::vector<std::uint8_t> encode_gray(const std::string& path, const std::string& extension, GrayView image) {
    if (extension != ".png" && extension != ".PNG")
        throw Error(path + ": this build of trnkit writes PNG only (the device kit, built without OpenCV imgcodecs); "
                           "name the file *.png");
    std::vector<std::uint8_t> bytes;
    PngErrors errors;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &errors, png_on_error, png_on_warning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!info) {
        png_destroy_write_struct(&png, nullptr);
        throw Error(path + ": out of memory starting the PNG encoder");
    }
    std::vector<png_bytep> rows(image.height);
    if (setjmp(errors.jump)) {
        png_destroy_write_struct(&png, &info);
        throw Error(path + ": cannot encode PNG (" + errors.message + ")");
    }
    png_set_write_fn(png, &bytes, append_bytes, no_flush);
    png_set_IHDR(png, info, image.width, image.height, 8, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    for (int y = 0; y < image.height; ++y) rows[y] = const_cast<png_bytep>(image.data + std::ptrdiff_t(y) * image.stride);
    png_set_rows(png, info, rows.data());
    png_write_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
    png_destroy_write_struct(&png, &info);
    return bytes;
}

const char* image_codec_name() { return "libpng (PNG only)"; }

}  // namespace trn::io::detail
