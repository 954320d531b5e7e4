#include "trn/sim/photo_import.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>

#include "trn/detail/angles.hpp"
#include "trn/error.hpp"
#include "trn/field_error.hpp"
#include "trn/io/geotiff.hpp"
#include "trn/io/input_file.hpp"
#include "trn/io/output_folder.hpp"
#include "trn/sim/air_format.hpp"
#include "trn/sim/geodesy.hpp"

namespace trn::sim {
namespace {

namespace fs = std::filesystem;

// Sensor widths from the makers' stated formats: 1/2.3" = 6.17 mm, 1/1.7" = 7.44 mm, 1" = 13.2 mm,
// 4/3" = 17.3 mm, APS-C (Sony) = 23.5 mm.
const std::vector<CameraSensor> kSensors = {
    {"Canon PowerShot SX260 HS", "Canon PowerShot SX260 HS (1/2.3\")", 6.17},
    {"Canon PowerShot SX230 HS", "Canon PowerShot SX230 HS (1/2.3\")", 6.17},
    {"Canon PowerShot S100", "Canon PowerShot S100 (1/1.7\")", 7.44},
    {"Canon PowerShot S110", "Canon PowerShot S110 (1/1.7\")", 7.44},
    {"FC300S", "DJI Phantom 3 Advanced (1/2.3\")", 6.17},
    {"FC300X", "DJI Phantom 3 Professional (1/2.3\")", 6.17},
    {"FC330", "DJI Phantom 4 (1/2.3\")", 6.17},
    {"FC6310", "DJI Phantom 4 Pro (1\")", 13.2},
    {"FC6310S", "DJI Phantom 4 Pro V2.0 (1\")", 13.2},
    {"FC220", "DJI Mavic Pro (1/2.3\")", 6.17},
    {"FC2103", "DJI Mavic Air (1/2.3\")", 6.17},
    {"FC2204", "DJI Mavic 2 Zoom (1/2.3\")", 6.17},
    {"L1D-20c", "DJI Mavic 2 Pro (Hasselblad, 1\")", 13.2},
    {"L2D-20c", "DJI Mavic 3 (Hasselblad, 4/3\")", 17.3},
    {"FC3411", "DJI Air 2S (1\")", 13.2},
    {"FC7203", "DJI Mavic Mini (1/2.3\")", 6.17},
    {"FC7303", "DJI Mini 2 (1/2.3\")", 6.17},
    {"FC1102", "DJI Spark (1/2.3\")", 6.17},
    {"FC6510", "DJI Zenmuse X4S (1\")", 13.2},
    {"FC6520", "DJI Zenmuse X5S (4/3\")", 17.3},
    {"DSC-RX100", "Sony RX100 (1\")", 13.2},
    {"ILCE-6000", "Sony a6000 (APS-C)", 23.5},
    {"ILCE-5100", "Sony a5100 (APS-C)", 23.5},
};

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::string num(double v, const char* fmt = "%.6g") {
    char buf[48];
    std::snprintf(buf, sizeof buf, fmt, v);
    return buf;
}

bool same(double a, double b) { return std::fabs(a - b) <= 1e-9 * std::max(std::fabs(a), std::fabs(b)); }

// The photos of a folder: its regular files (links to them too) not starting with '.', by name.
std::vector<std::string> list_photos(const std::string& dir) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw FieldError("photos", dir + ": not a folder");
    std::vector<std::string> names;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.empty() || name[0] == '.') continue;
        std::error_code e2;
        if (it->is_directory(e2)) continue;  // sub-folders are not photos (nor searched)
        // Its name goes into metadata.csv, which is read line by line: a newline there would split a row.
        if (std::any_of(name.begin(), name.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
            throw FieldError("photos", dir + "/" + io::quote_input(name) + ": a photo name with a control character (a newline would break "
                                                                          "metadata.csv's rows); rename the photo");
        names.push_back(name);
    }
    if (ec) throw FieldError("photos", dir + ": cannot list the folder (" + ec.message() + ")");
    std::sort(names.begin(), names.end());
    if (names.empty()) throw FieldError("photos", dir + ": no photos in the folder");
    return names;
}

}  // namespace

const std::vector<CameraSensor>& known_camera_sensors() { return kSensors; }

double known_sensor_width_mm(const std::string& model) {
    const std::string m = lower(model);
    for (const CameraSensor& s : kSensors)
        if (lower(s.model) == m) return s.sensor_width_mm;
    return NAN;
}

PhotoImportResult check_photo_set(std::vector<ImportedPhoto> photos, const PhotoImportOptions& o) {
    if (photos.empty()) throw FieldError("photos", o.photos + ": no photos in the folder");
    PhotoImportResult res;
    std::vector<std::string> rotated, without_gps;
    for (const ImportedPhoto& p : photos) {
        const std::string path = (fs::path(o.photos) / p.photo).string();
        if (std::isnan(p.exif.time_s))
            throw Error(path + ": EXIF DateTimeOriginal is missing; import-photos orders the photos by it and times the flight with it");
        if (std::isnan(p.exif.focal_length_mm))
            throw Error(path + ": EXIF FocalLength is missing; the field of view is computed from it and the sensor width");
        if (p.exif.orientation > 1) {
            if (!o.ignore_orientation)
                throw FieldError("ignore_orientation",
                                 path + ": EXIF Orientation " + std::to_string(p.exif.orientation) +
                                     " (the photo is to be shown rotated or mirrored); trnkit does not rotate frames by it, since a camera "
                                     "looking down cannot tell which way is up. Give `ignore_orientation` to use the pixels as stored "
                                     "(the sensor's own orientation, which turns with the drone), or undo the rotation first");
            rotated.push_back(p.photo);
        }
        if (!p.exif.gps) without_gps.push_back(p.photo);
    }
    // One camera at one focal length: the AIR folder has one field of view.
    const ImportedPhoto& first = photos.front();
    for (const ImportedPhoto& p : photos) {
        if (p.exif.model != first.exif.model || p.exif.make != first.exif.make)
            throw Error(o.photos + "/" + p.photo + ": taken with '" + io::quote_input(p.exif.make + " " + p.exif.model) + "', " + first.photo +
                        " with '" + io::quote_input(first.exif.make + " " + first.exif.model) + "'; import one camera's photos at a time");
        // Frames are scored at the camera's one size: another size would be scored at the wrong scale.
        if (p.exif.width != first.exif.width || p.exif.height != first.exif.height)
            throw Error(o.photos + "/" + io::quote_input(p.photo) + ": " + std::to_string(p.exif.width) + "x" + std::to_string(p.exif.height) +
                        " px, " + io::quote_input(first.photo) + " " + std::to_string(first.exif.width) + "x" + std::to_string(first.exif.height) +
                        " px; one AIR folder has one camera size: import each size's photos separately");
        if (!same(p.exif.focal_length_mm, first.exif.focal_length_mm))
            throw Error(o.photos + "/" + p.photo + ": EXIF FocalLength " + num(p.exif.focal_length_mm) + " mm differs from " + first.photo + "'s " +
                        num(first.exif.focal_length_mm) + " mm (zoomed between photos); one AIR folder has one field of view");
    }
    res.camera = first.exif.make.empty() ? first.exif.model : first.exif.model.rfind(first.exif.make, 0) == 0 ? first.exif.model
                                                                                                            : first.exif.make + " " + first.exif.model;
    res.focal_length_mm = first.exif.focal_length_mm;
    if (o.sensor_width_mm > 0) {
        res.sensor_width_mm = o.sensor_width_mm, res.sensor_width_source = "sensor_width_mm";
    } else {
        res.sensor_width_mm = known_sensor_width_mm(first.exif.model);
        if (std::isnan(res.sensor_width_mm) && std::isfinite(first.exif.sensor_width_mm))  // the camera's own word
            res.sensor_width_mm = first.exif.sensor_width_mm, res.sensor_width_source = "EXIF FocalPlaneXResolution";
        if (std::isnan(res.sensor_width_mm))
            throw FieldError("sensor_width_mm", "required: the camera '" + io::quote_input(first.exif.model.empty() ? "(no EXIF Model)" : first.exif.model) +
                                                    "' of " + o.photos + "/" + first.photo +
                                                    " is not in trnkit's table of sensor widths and its EXIF has no usable FocalPlaneXResolution; give its "
                                                    "sensor's width in mm (1/2.3\": 6.17)");
        for (const CameraSensor& s : kSensors)
            if (lower(s.model) == lower(first.exif.model)) res.sensor_width_source = s.name;
    }

    // Time order; equal times (EXIF's one-second resolution) by file name.
    std::stable_sort(photos.begin(), photos.end(), [](const ImportedPhoto& a, const ImportedPhoto& b) { return a.exif.time_s < b.exif.time_s; });
    std::size_t ties = 0;
    bool reordered = false;
    for (std::size_t i = 1; i < photos.size(); ++i) {
        ties += photos[i].exif.time_s == photos[i - 1].exif.time_s;
        reordered |= photos[i].photo < photos[i - 1].photo;
    }
    if (reordered) res.notes.push_back("the photos were ordered by EXIF DateTimeOriginal, which differs from their file names' order");
    if (ties) res.notes.push_back(std::to_string(ties) + " photos share their EXIF time with the one before; those are ordered by file name");
    const double t0 = photos.front().exif.time_s, span = photos.back().exif.time_s - t0;
    res.fps = photos.size() > 1 && span > 0 ? double(photos.size() - 1) / span : 1.0;
    // flight.json's fps is at most 1000 (localize refuses more): a burst 0.1 ms apart would write one
    // no reader takes. Refused here, before anything is written.
    if (res.fps > 1000)
        throw Error(o.photos + ": the " + std::to_string(photos.size()) + " photos span " + num(span, "%.3g") + " s by their EXIF times: " +
                    num(res.fps, "%.0f") + " photos/s, more than the 1000 an AIR folder may have (a burst?); import photos at least 1 ms apart");
    if (!rotated.empty())
        res.notes.push_back(std::to_string(rotated.size()) + " photos have an EXIF Orientation other than 1 (first: " + rotated.front() +
                            "); their pixels were used as stored");
    if (!without_gps.empty())
        res.notes.push_back(std::to_string(without_gps.size()) + " of " + std::to_string(photos.size()) + " photos have no GPS fix (first: " +
                            without_gps.front() + "); their Latitude,Longitude are left empty");
    res.gps_fixes = photos.size() - without_gps.size();

    // Field of view across the frame's width: the sensor width spans the longer side of the stored
    // pixels (square pixels), as a sensor is wider than high. (Every photo has the same size.)
    const io::PhotoExif& size = photos.front().exif;
    const double across = res.sensor_width_mm * std::min(1.0, double(size.width) / std::max(size.width, size.height));
    res.hfov_deg = 2 * std::atan(across / (2 * res.focal_length_mm)) / kDeg;
    for (ImportedPhoto& p : photos) p.time_s = p.exif.time_s - t0;
    res.photos = std::move(photos);
    return res;
}

PhotoImportResult import_photos(const PhotoImportOptions& o, const std::function<void(std::size_t, std::size_t)>& progress) {
    // Options first: a missing one costs nothing.
    if (o.out.empty()) throw FieldError("out", "required (the AIR folder to write)");
    if (!(o.altitude_agl_m > 0 && o.altitude_agl_m <= 20000))
        throw FieldError("altitude_agl_m", std::isnan(o.altitude_agl_m)
                                               ? "required: the camera's height above the ground in metres (EXIF GPS altitude is above sea "
                                                 "level and a camera's GPS altitude is unreliable, so trnkit never takes it from the photos)"
                                               : num(o.altitude_agl_m) + " m must be in (0, 20000]");
    if (o.sensor_width_mm != 0 && !(o.sensor_width_mm > 0 && o.sensor_width_mm <= 100))
        throw FieldError("sensor_width_mm", num(o.sensor_width_mm) + " mm must be in (0, 100]");
    if (o.width < 16 || o.width > 16384) throw FieldError("width", std::to_string(o.width) + " px must be in [16, 16384]");
    std::string map_file;
    if (!o.map.empty()) {
        std::error_code ec;
        if (!fs::is_regular_file(o.map, ec)) throw FieldError("map", o.map + ": not a file");
        if (!(o.metres_per_pixel > 0) && !io::has_geotiff_extension(o.map))
            throw FieldError("metres_per_pixel", "required with `map` " + o.map + " (not a GeoTIFF, whose georeference would give it)");
        map_file = fs::relative(fs::absolute(o.map), fs::absolute(fs::path(o.out)).lexically_normal(), ec).generic_string();
        if (ec || map_file.empty()) throw FieldError("map", o.map + ": no path from " + o.out + " to it (" + ec.message() + ")");
        if (o.map_origin)
            if (const std::string why = geo_origin_problem(*o.map_origin); !why.empty()) throw FieldError("map_origin", why);
    } else if (o.metres_per_pixel > 0 || o.map_origin) {
        throw FieldError("map", "required with `" + std::string(o.map_origin ? "map_origin" : "metres_per_pixel") + "` (they describe the map)");
    }

    // Every photo's EXIF before anything is written, checked as a set.
    std::vector<ImportedPhoto> read;
    for (const std::string& name : list_photos(o.photos)) {
        ImportedPhoto p;
        p.photo = name;
        p.exif = io::read_photo_exif((fs::path(o.photos) / name).string());
        read.push_back(std::move(p));
    }
    PhotoImportResult res = check_photo_set(std::move(read), o);
    std::vector<ImportedPhoto>& photos = res.photos;

    // The folder, built whole beside its target.
    io::StagedFolder staged(o.out, "import-photos", o.force);
    const std::string dir = staged.path();
    AirWriter writer(dir, {"Photo", "DateTimeOriginal", "TimeS"});
    char frame_name[32];
    for (std::size_t i = 0; i < photos.size(); ++i) {
        ImportedPhoto& p = photos[i];
        std::snprintf(frame_name, sizeof frame_name, "frame_%05zu.png", i);
        p.frame = frame_name;
        const GrayImage frame = io::load_photo_gray((fs::path(o.photos) / p.photo).string(), o.width);
        if (i == 0) res.frame_width = frame.width, res.frame_height = frame.height;
        AirRecord r;
        r.filename = p.frame;
        r.latitude_deg = p.exif.gps ? p.exif.gps->latitude_deg : NAN;
        r.longitude_deg = p.exif.gps ? p.exif.gps->longitude_deg : NAN;
        r.relative_altitude_m = o.altitude_agl_m;
        r.imu = r.orientation = {NAN, NAN, NAN, NAN};  // no compass, no truth
        r.pose_m = r.svo_m = {NAN, NAN, NAN};          // no truth, no recorded odometry
        r.map_x = r.map_y = NAN;
        writer.write(r, frame.view(), {p.photo, p.exif.datetime_original, num(p.time_s, "%.3f")});
        if (progress) progress(i + 1, photos.size());
    }
    writer.close();

    FlightInfo info;
    info.scenario = "photos " + o.photos + " (" + res.camera + ")";
    info.map_file = map_file;
    info.metres_per_pixel = o.metres_per_pixel;
    info.origin = o.map_origin;
    info.camera = {res.frame_width, res.frame_height, res.hfov_deg};
    info.camera.validate();
    info.fps = res.fps;
    info.frames = photos.size();
    info.latlon_source = kLatLonCameraGps;
    write_flight_info(dir + "/flight.json", info);
    staged.commit();
    return res;
}

}  // namespace trn::sim
