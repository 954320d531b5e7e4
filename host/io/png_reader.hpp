#pragma once
// A PNG file opened for libpng: shared by the device kit's PNG codec (image_codec_png.cpp) and the
// streamed no-data reader every build uses for PNG maps (png_validity.cpp).
#include <png.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <string>

#include "trn/error.hpp"
#include "trn/io/image_io.hpp"

namespace trn::io::detail {

// libpng reports errors through a callback that must not return: it records the message and jumps
// back to the setjmp in the calling function (no C++ exception crosses libpng's C frames).
struct PngErrors {
    std::jmp_buf jump;
    char message[256] = "";
};

[[noreturn]] inline void png_on_error(png_structp png, png_const_charp msg) {
    auto* errors = static_cast<PngErrors*>(png_get_error_ptr(png));
    std::snprintf(errors->message, sizeof errors->message, "%s", msg ? msg : "unknown libpng error");
    std::longjmp(errors->jump, 1);
}
inline void png_on_warning(png_structp, png_const_charp) {}  // OpenCV ignores libpng warnings too

// A PNG file opened for reading: its signature checked (else trn::Error "PATH: not a PNG file" and
// `not_png_hint`), libpng's read and info structs made and pointed at it (released with the object).
// Callers set their own setjmp(errors.jump) before the first libpng call that can fail: the jump
// must land in a frame that is still live.
class PngReader {
public:
    PngReader(const std::string& path, const std::string& not_png_hint) : file_(std::fopen(path.c_str(), "rb")) {
        if (!file_) throw Error(path + ": cannot open (" + std::strerror(errno) + ")");
        png_byte signature[8] = {};
        if (std::fread(signature, 1, 8, file_.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0)
            throw Error(path + ": not a PNG file" + not_png_hint);
        png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &errors, png_on_error, png_on_warning);
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
    struct FileCloser {
        void operator()(std::FILE* f) const { std::fclose(f); }
    };
    std::unique_ptr<std::FILE, FileCloser> file_;
};

// The no-data of a PNG file as load_validity states it (alpha 0, tRNS, or every colour channel equal
// to *nodata after 16-bit samples keep their high byte); empty when the file has no alpha or tRNS and
// nodata is not given. A file that is not PNG: "PATH: not a PNG file" and `not_png_hint`. A non-interlaced file is read row by row: the mask (1 B/px) and one row are
// all it holds; an interlaced one needs every row at once (8-bit RGBA, 4 B/px, and the mask).
GrayImage decode_png_validity(const std::string& path, std::optional<int> nodata, const std::string& not_png_hint);

}  // namespace trn::io::detail
