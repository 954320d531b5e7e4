// Image files through libpng alone: PNG in and out, nothing else (the device kit's libtrnkit_io, see
// image_codec.hpp). Reads as OpenCV's PNG decoder does for IMREAD_GRAYSCALE (the same libpng
// transformations), so a grey or colour PNG gives the same pixels in both builds.
#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>

#include "image_codec.hpp"
#include "trn/error.hpp"

namespace trn::io::detail {
namespace {

// libpng reports errors through a callback that must not return: it records the message and jumps
// back to the setjmp in the calling function (no C++ exception crosses libpng's C frames).
struct PngErrors {
    std::jmp_buf jump;
    char message[256] = "";
};

[[noreturn]] void on_error(png_structp png, png_const_charp msg) {
    auto* errors = static_cast<PngErrors*>(png_get_error_ptr(png));
    std::snprintf(errors->message, sizeof errors->message, "%s", msg ? msg : "unknown libpng error");
    std::longjmp(errors->jump, 1);
}
void on_warning(png_structp, png_const_charp) {}  // OpenCV ignores libpng warnings too

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};

[[noreturn]] void not_png(const std::string& path) {
    throw Error(path + ": not a PNG file; this build of trnkit reads PNG only (the device kit's image "
                       "reader, built without OpenCV imgcodecs): convert the image to PNG");
}

// A PNG file opened for reading: its signature checked, libpng's read and info structs made and
// pointed at it (released with the object). Callers set their own setjmp(errors.jump) before the
// first libpng call that can fail: the jump must land in a frame that is still live.
class PngReader {
public:
    explicit PngReader(const std::string& path) : file_(std::fopen(path.c_str(), "rb")) {
        if (!file_) throw Error(path + ": cannot open (" + std::strerror(errno) + ")");
        png_byte signature[8] = {};
        if (std::fread(signature, 1, 8, file_.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0) not_png(path);
        png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &errors, on_error, on_warning);
        info = png ? png_create_info_struct(png) : nullptr;
        if (!info) {
            png_destroy_read_struct(&png, nullptr, nullptr);
            throw Error(path + ": out of memory starting the PNG decoder");
        }
    }
    ~PngReader() { png_destroy_read_struct(&png, &info, nullptr); }
    PngReader(const PngReader&) = delete;
    PngReader& operator=(const PngReader&) = delete;
    // After the caller's setjmp: hands the file to libpng and reads the header.
    void start() {
        png_init_io(png, file_.get());
        png_set_sig_bytes(png, 8);
        png_read_info(png, info);
    }
    PngErrors errors;
    png_structp png = nullptr;
    png_infop info = nullptr;

private:
    std::unique_ptr<std::FILE, FileCloser> file_;
};

}  // namespace

GrayImage decode_gray(const std::string& path) {
    PngReader reader(path);
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

GrayImage decode_validity(const std::string& path, std::optional<int> nodata, int /*transparent_grey: libpng expands tRNS to alpha*/) {
    PngReader reader(path);
    png_structp png = reader.png;
    png_infop info = reader.info;
    GrayImage valid;
    std::vector<png_byte> rgba;
    std::vector<png_bytep> rows;
    if (setjmp(reader.errors.jump)) throw Error(path + ": cannot decode PNG (" + reader.errors.message + ")");
    reader.start();
    const int color_type = png_get_color_type(png, info);
    const bool alpha = (color_type & PNG_COLOR_MASK_ALPHA) != 0 || png_get_valid(png, info, PNG_INFO_tRNS);
    if (!alpha && !nodata) return {};
    // Every layout as 8-bit RGBA (opaque where the file has no alpha).
    png_set_expand(png);
    png_set_strip_16(png);
    png_set_gray_to_rgb(png);
    png_set_add_alpha(png, 0xFF, PNG_FILLER_AFTER);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    valid.width = static_cast<int>(png_get_image_width(png, info));
    valid.height = static_cast<int>(png_get_image_height(png, info));
    if (png_get_rowbytes(png, info) != 4 * static_cast<std::size_t>(valid.width)) png_error(png, "unexpected row layout after conversion to RGBA");
    rgba.resize(4 * std::size_t(valid.width) * valid.height);
    rows.resize(valid.height);
    for (int y = 0; y < valid.height; ++y) rows[y] = rgba.data() + 4 * std::size_t(y) * valid.width;
    png_read_image(png, rows.data());
    png_read_end(png, nullptr);
    valid.pixels.assign(std::size_t(valid.width) * valid.height, 255);
    for (std::size_t i = 0; i < valid.pixels.size(); ++i) {
        const png_byte* p = rgba.data() + 4 * i;
        if (p[3] == 0 || (nodata && p[0] == *nodata && p[1] == *nodata && p[2] == *nodata)) valid.pixels[i] = 0;
    }
    return valid;
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
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &errors, on_error, on_warning);
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
