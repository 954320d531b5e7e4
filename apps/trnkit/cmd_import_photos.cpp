// `trnkit import-photos DIR --out AIR`: a folder of geotagged camera photos (JPEG + EXIF) as an AIR
// flight folder that `trnkit localize` reads (trn/sim/photo_import.hpp does the work).
#include <charconv>
#include <cmath>
#include <iostream>

#include "commands.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "trn/io/photo.hpp"
#include "trn/sim/photo_import.hpp"

namespace trn::cli {
namespace {

struct ImportArgs {
    sim::PhotoImportOptions o;
    std::string map_origin;  // "LAT,LON", checked at parse time
};

// "LAT,LON" degrees, or false.
bool parse_latlon(const std::string& text, double& lat, double& lon) {
    const std::size_t comma = text.find(',');
    if (comma == std::string::npos) return false;
    const std::string a = text.substr(0, comma), b = text.substr(comma + 1);
    const auto ra = std::from_chars(a.data(), a.data() + a.size(), lat), rb = std::from_chars(b.data(), b.data() + b.size(), lon);
    return !a.empty() && !b.empty() && ra.ec == std::errc() && rb.ec == std::errc() && ra.ptr == a.data() + a.size() &&
           rb.ptr == b.data() + b.size() && lat >= -90 && lat <= 90 && lon >= -180 && lon <= 180;
}

void run(ImportArgs& a) {
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
    std::printf("no compass, ground truth or odometry in photos: localize with  trnkit localize --dataset %s --odometry visual%s%s\n",
                a.o.out.c_str(), a.o.map.empty() ? " --map MAP --mpp M" : "", r.gps_fixes ? " --start-from-gps RADIUS_M" : " --start X,Y");
}

}  // namespace

void add_import_photos_command(CLI::App& app) {
    auto a = std::make_shared<ImportArgs>();
    auto* cmd = app.add_subcommand("import-photos", "Make an AIR flight folder from a folder of geotagged camera photos (JPEG + EXIF)");
    cmd->add_option("DIR", a->o.photos, "Folder of JPEG photos (every file not starting with '.'; sub-folders are ignored)")->required();
    cmd->add_option("--out", a->o.out, "AIR folder to write (frames, metadata.csv, flight.json); replaced whole or not at all")->required();
    cmd->add_option("--altitude-agl", a->o.altitude_agl_m,
                    "Camera height above the ground, metres (required: EXIF GPS altitude is above sea level and unreliable, never used)")
        ->check(real_in(0, 20000, Open::low));
    cmd->add_option("--sensor-width-mm", a->o.sensor_width_mm,
                    "Camera sensor width, mm (default: from trnkit's table of common cameras by EXIF Model; 1/2.3\" sensors: 6.17)")
        ->check(real_in(0, 100, Open::low));
    cmd->add_option("--width", a->o.width, "Frame width in pixels (photos area-averaged, then grey 0.299 R + 0.587 G + 0.114 B)")
        ->capture_default_str()
        ->transform(whole_in(16, 16384));
    cmd->add_flag("--ignore-orientation", a->o.ignore_orientation,
                  "Use the stored pixels of photos whose EXIF Orientation is not 1 (default: refused; frames are never rotated by it)");
    cmd->add_option("--map", a->o.map, "Localization map for flight.json (optional; localize --map gives it otherwise)");
    cmd->add_option("--mpp", a->o.metres_per_pixel, "Its resolution, metres per pixel (required with a --map that is no GeoTIFF)")
        ->check(real_in(0, 1000, Open::low));
    cmd->add_option("--map-origin", a->map_origin,
                    "LAT,LON of the map's top-left pixel (a north-up map that is no GeoTIFF): localize --start-from-gps can then place fixes")
        ->check(CLI::Validator(
            [](std::string& t) -> std::string {
                double lat, lon;
                return parse_latlon(t, lat, lon) ? "" : "expected LAT,LON in degrees (two numbers separated by a comma), got '" + t.substr(0, 40) + "'";
            },
            "LAT,LON"));
    cmd->add_flag("--force", a->o.force, "Write into a non-empty folder that is not an earlier output of import-photos (its other files stay)");
    cmd->callback([a] { run(*a); });
}

}  // namespace trn::cli
