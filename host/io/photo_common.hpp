#pragma once
// Internals of photo_exiv2.cpp that need no exiv2: what a file is when it is no JPEG, and EXIF's
// date format as seconds.
#include <string>
#include <string_view>

namespace trn::io::detail {

// "" for a JPEG (FF D8 FF), else why not ("not a JPEG but a PNG image"; "empty file").
std::string not_jpeg(std::string_view bytes);

// "YYYY:MM:DD HH:MM:SS" (+ SubSecTime digits) as seconds since 1970-01-01 00:00:00 of the same
// clock (the camera's; EXIF states no time zone). NaN for the blank or all-zero "unknown" date EXIF
// allows; anything else that is no date throws trn::Error naming `name` and the tag.
double exif_time_s(const std::string& datetime, const std::string& subsec, const std::string& name);

}  // namespace trn::io::detail
