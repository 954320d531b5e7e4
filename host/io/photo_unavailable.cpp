// The device kit's io layer reads no camera photos (no exiv2, PNG only): the same functions, each an
// Error saying so.
#include "trn/error.hpp"
#include "trn/io/photo.hpp"

namespace trn::io {
namespace {
[[noreturn]] void unavailable(const std::string& name) {
    throw Error(name + ": camera photos (JPEG + EXIF) are not readable with this build's io layer (the device kit's: PNG only, no "
                       "exiv2); import the photos with a full trnkit build");
}
}  // namespace

PhotoExif parse_photo_exif(std::string_view, const std::string& name) { unavailable(name); }
PhotoExif read_photo_exif(const std::string& path) { unavailable(path); }
GrayImage load_photo_gray(const std::string& path, int) { unavailable(path); }
std::string photo_reader_name() { return "none (the device kit's io layer)"; }

}  // namespace trn::io
