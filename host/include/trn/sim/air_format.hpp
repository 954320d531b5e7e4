#pragma once
// The AIR dataset layout: one folder per flight with the camera images and metadata.csv, one row
// per image, columns (units as the dissertation's Table 2.3 uses them):
//   Filename                      image file, relative to the folder (may be quoted)
//   Latitude, Longitude           degrees (WGS84)
//   RelativeAltitude              metres above the take-off ground
//   ImuX, ImuY, ImuZ, ImuW        attitude quaternion as the IMU/magnetometer measures it (ENU, FLU body)
//   PoseX, PoseY, PoseZ           true position, metres east / north / up from the start point
//   OrientationX, Y, Z, W         true attitude quaternion (ENU, FLU body)
//   MapX, MapY                    true position in map pixels (x east, y south)
//   SvoX, SvoY, SvoZ              visual odometry position, metres, same frame as Pose
// Optional, read when the header has it (trnkit import-photos writes it; simulate does not):
//   TimeS                         when the frame was taken, seconds on one clock (empty: unknown);
//                                 never decreasing down the rows. Without it a frame's time is its
//                                 row over the folder's fps.
// Groups of columns a flight may not have are left empty in every cell of the group (NaN in
// AirRecord; the writer writes NaN as an empty cell): Latitude,Longitude (no position fix);
// ImuX..W (no attitude measured: heading unknown, the camera taken as level at nadir);
// PoseX..Z, OrientationX..W and MapX,MapY (no ground truth); SvoX..Z (no recorded odometry: only
// visual odometry can be used). A group partly empty is a broken row. Camera photos
// (`trnkit import-photos`) have no attitude, truth or odometry, and their Latitude/Longitude are the
// camera's GPS (flight.json's latlon_source).
// The reader takes columns in any order, ignores extra ones, streams rows (a real flight has
// 16,000) and reports a malformed row by file and line number: besides unparsable fields, values
// no flight can have (latitude beyond 90, |MapX| > 1e7, a quaternion not of length 1) and rows
// duplicated or out of frame order (by the number a file name ends with). flight.json next to it (written by
// `trnkit simulate`) names the map, its resolution and the camera.
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "trn/io/input_file.hpp"
#include "trn/sim/camera.hpp"
#include "trn/sim/flight.hpp"
#include "trn/sim/map.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::sim {

struct Quaternion {
    double x = 0, y = 0, z = 0, w = 1;
};

// Attitude quaternion (ENU world, x-forward/y-left/z-up body) from compass heading, roll, pitch.
Quaternion attitude_quaternion(double heading_rad, double roll_rad = 0, double pitch_rad = 0);
// Compass heading (0 north, pi/2 east) of such a quaternion.
double heading_from_quaternion(const Quaternion& q);
// Roll and pitch of such a quaternion (the inverse of attitude_quaternion's), radians: what a
// camera fixed to the body (no gimbal) sees tilted by. A real AIR flight carries them in ImuX..W.
struct RollPitch {
    double roll_rad = 0, pitch_rad = 0;
};
RollPitch roll_pitch_from_quaternion(const Quaternion& q);
// Angle between the optical axis of a camera tilted by roll and pitch and the vertical, radians.
double tilt_from_nadir(double roll_rad, double pitch_rad);

struct AirRecord {
    std::string filename;
    double latitude_deg = 0, longitude_deg = 0;
    double relative_altitude_m = 0;
    Quaternion imu;
    Vec3 pose_m;
    Quaternion orientation;
    double map_x = 0, map_y = 0;
    Vec3 svo_m;
    double time_s = NAN;  // the optional TimeS column (NaN: absent or empty); the writer leaves it to extra columns
};

AirRecord make_air_record(const FlightFrame& frame, const std::string& filename);

// The column names in the order the writer uses.
const std::vector<std::string>& air_columns();

// Everything about a flight that is not per frame: written as flight.json.
struct FlightInfo {
    std::string scenario;
    std::string map_file;          // localization map, relative to the flight folder ("" if none)
    double metres_per_pixel = 1;   // of that map; 0 (left out of flight.json): not stated (no map, or a GeoTIFF's own)
    std::optional<GeoOrigin> origin;
    Camera camera;
    double fps = 50;
    int map_year = 0;              // year of the localization map (0: unknown)
    int rendered_year = 0;         // year of the map the frames were rendered from
    std::uint64_t seed = 0;
    std::size_t frames = 0;        // rows metadata.csv must have (0: not declared); a shorter file is cut
    // What metadata.csv's Latitude/Longitude are: "" (not stated; simulate's are the truth),
    // "truth", or kLatLonCameraGps: a camera's GPS fixes, a reference track that lags and drifts
    // (seconds, metres), never ground truth.
    std::string latlon_source;
};
inline constexpr const char* kLatLonCameraGps = "camera_gps";
void write_flight_info(const std::string& path, const FlightInfo& info);
FlightInfo read_flight_info(const std::string& path);

class AirWriter {
public:
    // Creates the folder (and parents). metadata.csv appears only at close(), complete: a run
    // that stops early leaves no metadata.csv rather than a cut one. Extra columns (after the AIR
    // ones; readers ignore them) carry what the format has no column for.
    explicit AirWriter(const std::string& folder, std::vector<std::string> extra_columns = {});
    // Writes the image (when not empty) under record.filename and keeps the row for close(). NaN
    // fields are empty cells: a whole group of optional columns or none (see above); `extra`
    // has one value per extra column.
    void write(const AirRecord& record, GrayView image = {}, const std::vector<std::string>& extra = {});
    void close();  // writes metadata.csv whole; throws naming the file when the write failed
    const std::string& folder() const { return folder_; }

private:
    std::string folder_;
    std::vector<std::string> extra_columns_;
    std::string csv_;  // metadata.csv so far
    bool closed_ = false;
};

// Parses metadata.csv rows from any stream.
class AirMetadataParser {
public:
    AirMetadataParser(std::istream& in, std::string source_name);
    // Next row; false at the end. Throws trn::Error "source:line: reason" on a malformed row.
    bool next(AirRecord& record);
    int line() const { return line_; }  // line number of the last row read (1 = header)

private:
    void check_order(const std::string& filename, const std::string& at);
    double parse_time(const std::string& field, const std::string& at);

    std::istream& in_;
    std::string source_;
    int line_ = 0;
    std::vector<int> column_of_;  // for each AIR column, its index in the file
    std::size_t field_count_ = 0;
    std::unordered_map<std::string, int> first_line_of_;  // file name -> line it was first listed on
    std::string last_number_, last_filename_;              // the last row whose name ends in a frame number
    int time_column_ = -1;                                 // TimeS, optional (-1: absent)
    double last_time_s_ = NAN;                             // the last row's TimeS
};

// Streams a flight folder.
class AirReader {
public:
    explicit AirReader(const std::string& folder);
    // Next row; false at the end. Throws when the file has no rows at all (header only).
    bool next(AirRecord& record);
    int line() const { return parser_->line(); }
    std::string image_path(const AirRecord& record) const;
    GrayImage load_image(const AirRecord& record) const;
    const std::string& folder() const { return folder_; }
    // metadata.csv as it was read (whole, at most io::kMaxTableFileBytes); true while the file
    // at that path is still the one read: a dataset replaced meanwhile (simulate rewriting it)
    // would pair these rows with other frames.
    bool unchanged() const;
    const io::FileIdentity& identity() const { return identity_; }

private:
    std::string folder_;
    std::string text_;
    io::FileIdentity identity_;
    std::unique_ptr<std::streambuf> buffer_;
    std::unique_ptr<std::istream> stream_;
    std::unique_ptr<AirMetadataParser> parser_;
    std::size_t rows_ = 0;
};

}  // namespace trn::sim
TRN_API_END
