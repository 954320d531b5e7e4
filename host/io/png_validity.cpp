// The no-data mask of a PNG map, streamed through libpng (see png_reader.hpp): every build reads
// PNG masks here, so a map's mask costs 1 B/px and a row, not a second full-depth decode of it.
#include <png.h>

#include <vector>

#include "png_reader.hpp"

namespace trn::io::detail {

GrayImage decode_png_validity(const std::string& path, std::optional<int> nodata, const std::string& not_png_hint) {
    PngReader reader(path, not_png_hint);
    png_structp png = reader.png;
    png_infop info = reader.info;
    GrayImage valid;
    std::vector<png_byte> rgba;  // one row, or every row of an interlaced file
    std::vector<png_bytep> rows;
    if (setjmp(reader.errors.jump)) throw Error(path + ": cannot decode PNG (" + reader.errors.message + ")");
    reader.start();
    const int color_type = png_get_color_type(png, info);
    const bool alpha = (color_type & PNG_COLOR_MASK_ALPHA) != 0 || png_get_valid(png, info, PNG_INFO_tRNS);
    if (!alpha && !nodata) return {};
    // Every layout as 8-bit RGBA (opaque where the file has no alpha): expand palettes, low bit
    // depths and tRNS to alpha, keep the high byte of 16-bit samples.
    png_set_expand(png);
    png_set_strip_16(png);
    png_set_gray_to_rgb(png);
    png_set_add_alpha(png, 0xFF, PNG_FILLER_AFTER);
    const int passes = png_set_interlace_handling(png);
    png_read_update_info(png, info);
    valid.width = static_cast<int>(png_get_image_width(png, info));
    valid.height = static_cast<int>(png_get_image_height(png, info));
    const std::size_t row_bytes = 4 * static_cast<std::size_t>(valid.width);
    if (png_get_rowbytes(png, info) != row_bytes) png_error(png, "unexpected row layout after conversion to RGBA");
    valid.pixels.assign(std::size_t(valid.width) * valid.height, 255);
    const auto mark_row = [&](const png_byte* p, int y) {
        std::uint8_t* out = valid.pixels.data() + std::size_t(y) * valid.width;
        for (int x = 0; x < valid.width; ++x, p += 4)
            if (p[3] == 0 || (nodata && p[0] == *nodata && p[1] == *nodata && p[2] == *nodata)) out[x] = 0;
    };
    if (passes == 1) {
        rgba.resize(row_bytes);
        for (int y = 0; y < valid.height; ++y) {
            png_read_row(png, rgba.data(), nullptr);
            mark_row(rgba.data(), y);
        }
    } else {  // Adam7: each pass adds pixels to rows read before, so all rows stay until the last pass
        rgba.resize(row_bytes * valid.height);
        rows.resize(valid.height);
        for (int y = 0; y < valid.height; ++y) rows[y] = rgba.data() + row_bytes * y;
        png_read_image(png, rows.data());
        for (int y = 0; y < valid.height; ++y) mark_row(rows[y], y);
    }
    png_read_end(png, nullptr);
    return valid;
}

}  // namespace trn::io::detail
