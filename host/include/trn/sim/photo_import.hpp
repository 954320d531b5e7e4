#pragma once
// A folder of geotagged camera photos (JPEG + EXIF) as an AIR flight folder (`trnkit import-photos`):
// photos ordered by their EXIF time, reduced to grey frames, the field of view from the focal length
// and the sensor width (a table of common cameras, or given), the height above ground given (EXIF's
// GPS altitude is above sea level and unreliable: never used), every GPS fix kept as Latitude /
// Longitude with flight.json's latlon_source "camera_gps" (a reference track, not the truth). The
// rows have no attitude, ground truth or recorded odometry (those columns are empty,
// air_format.hpp): localize them with visual odometry.
//
// metadata.csv's extra columns: Photo (the source file's name), DateTimeOriginal (as EXIF states
// it) and TimeS (seconds since the first photo, SubSecTimeOriginal included when present).
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "trn/io/photo.hpp"
#include "trn/sim/map.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::sim {

// Sensor widths of common cameras by EXIF Model (case-insensitive), millimetres.
struct CameraSensor {
    const char* model;  // as Exif.Image.Model states it
    const char* name;   // what it is (for messages)
    double sensor_width_mm;
};
const std::vector<CameraSensor>& known_camera_sensors();
// The table's width for this model, or NaN.
double known_sensor_width_mm(const std::string& model);

// Errors are trn::FieldError naming these fields (the CLI maps them to its flags), or trn::Error
// naming the photo and the EXIF tag.
struct PhotoImportOptions {
    std::string photos;              // folder of photos: every regular file not starting with '.'
    std::string out;                 // the AIR folder written (a StagedFolder: replaced whole, or not at all)
    double altitude_agl_m = NAN;     // required: the camera's height above the ground, metres
    double sensor_width_mm = 0;      // 0: from known_camera_sensors()
    int width = 455;                 // frame width, pixels (photos reduced by area averaging)
    bool ignore_orientation = false; // use the stored pixels of photos whose EXIF Orientation is not 1
    std::string map;                 // optional: the localization map flight.json names (relative to `out`)
    double metres_per_pixel = 0;     // its resolution (required with a map that is no GeoTIFF)
    std::optional<GeoOrigin> map_origin;  // latitude/longitude of its pixel (0, 0) (needs `map`)
    bool force = false;
};

struct ImportedPhoto {
    std::string photo;     // the source file's name within the folder
    std::string frame;     // the frame written (frame_00000.png ...)
    double time_s = 0;     // since the first photo
    io::PhotoExif exif;
};

struct PhotoImportResult {
    std::vector<ImportedPhoto> photos;  // in time order, as the rows are
    std::string camera;                 // make and model
    double focal_length_mm = 0, sensor_width_mm = 0, hfov_deg = 0, fps = 0;
    std::string sensor_width_source;    // "--sensor-width-mm" or the table entry's name
    std::size_t gps_fixes = 0;
    int frame_width = 0, frame_height = 0;  // of the first frame
    std::vector<std::string> notes;     // what the user should know (photos reordered, fixes missing ...)
};

// The checks and facts of a set of photos from their EXIF alone, import_photos's first half: each
// has DateTimeOriginal and FocalLength (and Orientation 1 unless ignore_orientation), all come from
// one camera at one focal length and one size, at most 1000 photos/s; the sensor width (given, the
// table's, or EXIF's FocalPlaneXResolution), the field of view, the photo rate, the GPS fixes and
// the notes. Returns them with `photos` in time order (time_s set). `options.photos` names the
// folder in messages. Throws as import_photos does.
PhotoImportResult check_photo_set(std::vector<ImportedPhoto> photos, const PhotoImportOptions& options);

// Reads every photo's EXIF first (a photo the import cannot use fails before any frame is made),
// then writes the frames, metadata.csv and flight.json. `progress(done, total)` after each frame.
PhotoImportResult import_photos(const PhotoImportOptions& options, const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace trn::sim
TRN_API_END
