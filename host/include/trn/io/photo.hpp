#pragma once
// Camera photos (JPEG with EXIF) for `trnkit import-photos`: the EXIF tags a flight needs, read with
// exiv2 (Debian's libexiv2), and the photo reduced to a grey frame. A JPEG only: anything else, or a
// file exiv2 or the decoder cannot read, is a trn::Error naming the file. The device kit's io layer
// (PNG only) has neither and says so (photo_unavailable.cpp).
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "trn/io/image_io.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::io {

// Largest photo file read (a 100-megapixel JPEG is ~50 MB).
inline constexpr std::uint64_t kMaxPhotoFileBytes = std::uint64_t{256} << 20;

struct GpsFix {
    double latitude_deg = 0, longitude_deg = 0;  // WGS84, signed from the N/S and E/W references
    double altitude_m = NAN;                     // GPSAltitude above sea level as stated (NaN: absent); not a height above ground
};

// What EXIF says; a tag that is absent is empty / NaN / 0. A tag that is present but malformed (a
// zero denominator, a latitude without its reference, a date that is no date) is an Error naming
// the file and the tag, never read as absent.
struct PhotoExif {
    int width = 0, height = 0;         // of the stored pixels (the JPEG frame header)
    std::string make, model;           // Exif.Image.Make / Model, trimmed
    std::string datetime_original;     // Exif.Photo.DateTimeOriginal "YYYY:MM:DD HH:MM:SS" as stated
    double time_s = NAN;               // it (+ SubSecTimeOriginal) as seconds since 1970 in the camera's clock (NaN: absent)
    double focal_length_mm = NAN;      // Exif.Photo.FocalLength
    int orientation = 0;               // Exif.Image.Orientation 1..8 (0: absent)
    double sensor_width_mm = NAN;      // from FocalPlaneXResolution (+ unit, PixelXDimension); NaN: absent or implausible
    std::optional<GpsFix> gps;         // GPSLatitude/Longitude (+Ref); absent, or GPSStatus V (void): none
};

// The EXIF of a JPEG in memory; `name` (the file) starts every error message.
PhotoExif parse_photo_exif(std::string_view bytes, const std::string& name);
// The same of a file (the checked open of input_file.hpp, at most kMaxPhotoFileBytes).
PhotoExif read_photo_exif(const std::string& path);

// The photo's stored pixels (EXIF orientation not applied) reduced to `width` pixels wide (the height
// in proportion, rounded) by area averaging of the colour image, then converted to grey as
// 0.299 R + 0.587 G + 0.114 B: decoded at 1/8, 1/4 or 1/2 scale in the JPEG's DCT domain (block
// means) while that stays at least `width` wide, then OpenCV's INTER_AREA and BGR2GRAY. A width at
// least the photo's keeps its size.
GrayImage load_photo_gray(const std::string& path, int width);

// Which library reads EXIF in this build ("exiv2 0.27.6"; the device kit: "none").
std::string photo_reader_name();

}  // namespace trn::io
TRN_API_END
