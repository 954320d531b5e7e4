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

// The sensor's width in mm from EXIF FocalPlaneXResolution (pixels per unit of
// FocalPlaneResolutionUnit: 2 inch, the default; 3 cm; 4 mm; 5 micrometre) over the width the camera
// recorded (PixelXDimension; `recorded_px` <= 0: none, then the stored width): a photo resized after
// the camera keeps its EXIF, so the recorded width is the one the resolution refers to. NaN when the
// result is no plausible sensor (outside 1..100 mm) or a value is unusable: the caller then needs
// another source, never a wrong field of view.
double focal_plane_sensor_width_mm(double resolution, long unit, double recorded_px, double stored_px);

}  // namespace trn::io::detail
