#include "photo_import_options.hpp"

#include <charconv>
#include <cstdio>
#include <iostream>

#include "options.hpp"
#include "progress.hpp"
#include "trn/sim/geodesy.hpp"
#include "trn/io/photo.hpp"

namespace trn::cli {
namespace {

// "LAT,LON" degrees, or false.
bool parse_latlon(const std::string& text, double& lat, double& lon) {
    const std::size_t comma = text.find(',');
    if (comma == std::string::npos) return false;
    const std::string a = text.substr(0, comma), b = text.substr(comma + 1);
    const auto ra = std::from_chars(a.data(), a.data() + a.size(), lat), rb = std::from_chars(b.data(), b.data() + b.size(), lon);
    return !a.empty() && !b.empty() && ra.ec == std::errc() && rb.ec == std::errc() && ra.ptr == a.data() + a.size() &&
           rb.ptr == b.data() + b.size() && lat >= -90 && lat <= 90 && lon >= -180 && lon <= 180;
}

}  // namespace

void add_photo_import_options(CLI::App& cmd, PhotoImportArgs& a) {
    cmd.add_option("--altitude-agl", a.o.altitude_agl_m,
                   "Camera height above the ground, metres (required: EXIF GPS altitude is above sea level and unreliable, never used)")
        ->check(real_in(0, 20000, Open::low));
    cmd.add_option("--sensor-width-mm", a.o.sensor_width_mm,
                   "Camera sensor width, mm (default: from trnkit's table of common cameras by EXIF Model; 1/2.3\" sensors: 6.17)")
        ->check(real_in(0, 100, Open::low));
    cmd.add_flag("--ignore-orientation", a.o.ignore_orientation,
                 "Use the stored pixels of photos whose EXIF Orientation is not 1 (default: refused; frames are never rotated by it)");
    cmd.add_option("--map-origin", a.map_origin,
                   "LAT,LON of the map's top-left pixel (a north-up map that is no GeoTIFF): the photos' GPS fixes can then be placed on it")
        ->check(CLI::Validator(
            [](std::string& t) -> std::string {
                double lat, lon;
                if (!parse_latlon(t, lat, lon)) return "expected LAT,LON in degrees (two numbers separated by a comma), got '" + t.substr(0, 40) + "'";
                return sim::geo_origin_problem({lat, lon});
            },
            "LAT,LON"));
}

sim::PhotoImportResult run_photo_import(PhotoImportArgs& a) {
    if (!a.map_origin.empty()) {
        double lat = 0, lon = 0;
        parse_latlon(a.map_origin, lat, lon);  // checked by the option's validator
        a.o.map_origin = sim::GeoOrigin{lat, lon};
    }
    std::cerr << "importing the photos of " << a.o.photos << " (EXIF: " << io::photo_reader_name() << ")\n";
    const sim::PhotoImportResult r =
        sim::import_photos(a.o, [](std::size_t done, std::size_t total) { draw_progress(done, total, "photos"); });
    for (const std::string& n : r.notes) std::cerr << "trnkit: note: " << n << "\n";
    std::printf("%zu photos -> %s: %dx%d grey frames, %s, focal length %.3g mm, sensor %.3g mm wide (%s): hfov %.2f deg; "
                "%.3g photos/s; height above ground %g m (--altitude-agl); %zu GPS fixes kept as Latitude,Longitude (camera GPS: "
                "a reference track, not the truth)\n",
                r.photos.size(), a.o.out.c_str(), r.frame_width, r.frame_height, r.camera.c_str(), r.focal_length_mm, r.sensor_width_mm,
                r.sensor_width_source == "sensor_width_mm" ? "--sensor-width-mm" : r.sensor_width_source.c_str(), r.hfov_deg, r.fps,
                a.o.altitude_agl_m, r.gps_fixes);
    std::fflush(stdout);
    return r;
}

}  // namespace trn::cli
