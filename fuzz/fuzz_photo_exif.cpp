// Fuzz entry: the EXIF reader of camera photos (host/io/photo_exiv2.cpp, parse_photo_exif over
// exiv2). A refusal must be trn::Error (never an exiv2 or standard exception escaping, never a
// crash); what it accepts is within the ranges the import relies on.
#include <cmath>

#include "fuzz_check.hpp"
#include "trn/error.hpp"
#include "trn/io/photo.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using trn::fuzz::require;
    trn::io::PhotoExif e;
    try {
        e = trn::io::parse_photo_exif(trn::fuzz::as_text(data, size), "fuzz.jpg");
    } catch (const trn::Error&) {
        return 0;
    }
    require(e.width > 0 && e.height > 0, "a photo without a size accepted");
    require(std::isnan(e.time_s) || std::isfinite(e.time_s), "an infinite time accepted");
    require(std::isnan(e.time_s) == e.datetime_original.empty(), "a time without its DateTimeOriginal text (or the reverse)");
    require(std::isnan(e.focal_length_mm) || (e.focal_length_mm > 0 && e.focal_length_mm < 10000), "a focal length out of range accepted");
    require(e.orientation >= 0 && e.orientation <= 8, "an orientation out of 0..8 accepted");
    if (e.gps) {
        require(std::fabs(e.gps->latitude_deg) <= 90, "a latitude beyond 90 accepted");
        require(std::fabs(e.gps->longitude_deg) <= 180, "a longitude beyond 180 accepted");
    }
    return 0;
}
