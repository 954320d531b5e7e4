// `trnkit import-photos DIR --out AIR`: a folder of geotagged camera photos (JPEG + EXIF) as an AIR
// flight folder that `trnkit localize` reads (trn/sim/photo_import.hpp does the work).
#include <cstdio>

#include "commands.hpp"
#include "options.hpp"
#include "photo_import_options.hpp"

namespace trn::cli {
namespace {

void run(PhotoImportArgs& a) {
    const sim::PhotoImportResult r = run_photo_import(a);
    std::printf("no compass, ground truth or odometry in photos: localize with  trnkit localize --dataset %s --odometry visual --heading none%s%s\n",
                a.o.out.c_str(), a.o.map.empty() ? " --map MAP --mpp M" : "", r.gps_fixes ? " --start-from-gps RADIUS_M" : " --start X,Y");
}

}  // namespace

void add_import_photos_command(CLI::App& app) {
    auto a = std::make_shared<PhotoImportArgs>();
    auto* cmd = app.add_subcommand("import-photos", "Make an AIR flight folder from a folder of geotagged camera photos (JPEG + EXIF)");
    cmd->add_option("DIR", a->o.photos, "Folder of JPEG photos (every file not starting with '.'; sub-folders are ignored)")->required();
    cmd->add_option("--out", a->o.out, "AIR folder to write (frames, metadata.csv, flight.json); replaced whole or not at all")->required();
    cmd->add_option("--width", a->o.width, "Frame width in pixels (photos area-averaged, then grey 0.299 R + 0.587 G + 0.114 B)")
        ->capture_default_str()
        ->transform(whole_in(16, 16384));
    cmd->add_option("--map", a->o.map, "Localization map for flight.json (optional; localize --map gives it otherwise)");
    cmd->add_option("--mpp", a->o.metres_per_pixel, "Its resolution, metres per pixel (required with a --map that is no GeoTIFF)")
        ->check(real_in(0, 1000, Open::low));
    add_photo_import_options(*cmd, *a);
    cmd->add_flag("--force", a->o.force, "Write into a non-empty folder that is not an earlier output of import-photos (its other files stay)");
    cmd->callback([a] { run(*a); });
}

}  // namespace trn::cli
