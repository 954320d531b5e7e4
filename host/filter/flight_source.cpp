#include "trn/filter/flight_source.hpp"

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <filesystem>
#include <optional>

#include "trn/error.hpp"
#include "trn/io/image_header.hpp"
#include "trn/io/input_file.hpp"
#include "trn/limits.hpp"
#include "trn/filter/nadir_warp.hpp"
#include "trn/sim/render.hpp"

namespace trn::filter {

namespace {

// Tilt of the optical axis from the vertical by the measured attitude (ImuX..W), degrees.
double tilt_deg(const sim::AirRecord& r) {
    const sim::RollPitch rp = sim::roll_pitch_from_quaternion(r.imu);
    return filter::tilt_deg(rp.roll_rad, rp.pitch_rad);
}

std::string place(const sim::AirReader& r, const std::string& filename) {
    return r.folder() + "/metadata.csv:" + std::to_string(r.line()) + " (" + filename + ")";
}

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

// A frame's size from its header; nullopt when the header cannot be read (the frame's load reports
// that during the run, as a missing frame).
std::optional<ImageSize> header_size(const std::string& path) {
    try {
        return read_image_size(path);
    } catch (const Error&) {
        return std::nullopt;
    }
}

}  // namespace

std::string frame_size_problem(int width, int height, int ref_width, int ref_height) {
    if (width <= 0 || height <= 0 || ref_width <= 0 || ref_height <= 0) return "a size of 0 px";
    const double expected = double(width) * ref_height / ref_width;  // the reference's view at this width
    if (std::fabs(height - expected) <= std::max(1.0, 0.01 * expected)) return "";
    return "another aspect ratio (" + number(double(width) / height) + " against " + number(double(ref_width) / ref_height) +
           "), so not the same view at another resolution (a crop, a rotated frame or another camera) and its scale from its width "
           "would be wrong; give such frames their own folder";
}

AirFlightSource::AirFlightSource(const std::string& folder, const sim::Camera& camera, double metres_per_pixel,
                                 double fps, std::size_t stride, std::size_t frames_hint, MapExtent map, double max_tilt_deg,
                                 bool camera_size_stated)
    : reader_(folder), camera_(camera), camera_size_stated_(camera_size_stated), mpp_(metres_per_pixel), fps_(fps), max_tilt_deg_(max_tilt_deg), stride_(stride), hint_(frames_hint) {
    if (!(fps > 0)) throw Error("AirFlightSource: fps must be > 0");
    if (!(max_tilt_deg >= 0 && max_tilt_deg < 90)) throw Error("AirFlightSource: max_tilt_deg must be in [0, 90)");
    if (stride == 0) throw Error("AirFlightSource: stride must be >= 1");
    if (!(metres_per_pixel > 0)) throw Error("AirFlightSource: metres_per_pixel must be > 0");
    camera.validate();
    check_rows(map);
}

// One pass over the rows before the run (16,000 rows take milliseconds; decoding images would not,
// so frames are only looked for).
void AirFlightSource::check_rows(MapExtent map) {
    sim::AirReader rows(reader_.folder());
    sim::AirRecord r;
    std::size_t count = 0, used = 0, missing = 0, odometry_off = 0, oblique = 0;
    std::string first_missing, first_odometry_off, first_oblique;
    // The size every frame must be a resized view of: the stated camera's, else the first frame's.
    int ref_w = camera_size_stated_ ? camera_.width : 0, ref_h = camera_size_stated_ ? camera_.height : 0;
    std::string ref_what = "the folder's camera (flight.json)";
    double start_x = 0, start_y = 0, svo_e0 = 0, svo_n0 = 0;
    while (rows.next(r)) {
        const std::string at = place(rows, r.filename) + ": ";  // RelativeAltitude in (0, 20000] m: AirMetadataParser's check
        const bool has_truth = std::isfinite(r.map_x) && std::isfinite(r.map_y);  // empty MapX/MapY: a flight without truth
        const bool off_map = has_truth && map.width > 0 && map.height > 0 &&
                             !(r.map_x >= 0 && r.map_x < map.width && r.map_y >= 0 && r.map_y < map.height);
        if (off_map)
            throw Error(at + "the true position MapX,MapY " + number(r.map_x) + "," + number(r.map_y) + " is outside the " +
                        std::to_string(map.width) + "x" + std::to_string(map.height) + " px map; the map does not cover the flight");
        if (count == 0) start_x = r.map_x, start_y = r.map_y, svo_e0 = r.svo_m.x, svo_n0 = r.svo_m.y;
        // Odometry placed on the map from the start (as the localizer does): drifting off it is
        // worth knowing, but the filter copes (particles off the map are flagged, not used).
        const double ox = start_x + (r.svo_m.x - svo_e0) / mpp_, oy = start_y - (r.svo_m.y - svo_n0) / mpp_;
        if (has_truth && std::isfinite(start_x) && map.width > 0 && map.height > 0 && !(ox >= 0 && ox < map.width && oy >= 0 && oy < map.height))
            if (odometry_off++ == 0) first_odometry_off = place(rows, r.filename);
        if (count++ % stride_ == 0) {
            ++used;
            if (tilt_deg(r) > max_tilt_deg_ && oblique++ == 0) first_oblique = place(rows, r.filename) + ", tilt " + number(tilt_deg(r)) + " deg";
            std::error_code ec;
            const std::string image = rows.image_path(r);
            if (!std::filesystem::is_regular_file(image, ec)) {
                if (missing++ == 0) first_missing = place(rows, r.filename);
            } else if (const std::optional<ImageSize> size = header_size(image);
                       size && size->width <= limits::kMaxImageSide && size->height <= limits::kMaxImageSide) {  // the header only: no decoding
                const int w = static_cast<int>(size->width), h = static_cast<int>(size->height);  // larger: refused by the load
                if (ref_w == 0) {
                    ref_w = w, ref_h = h, ref_what = "the first frame (" + image + ")";
                } else if (const std::string why = frame_size_problem(w, h, ref_w, ref_h); !why.empty()) {
                    throw Error(place(rows, r.filename) + ": the frame " + image + " is " + std::to_string(w) + "x" + std::to_string(h) +
                                " px, but " + ref_what + " is " + std::to_string(ref_w) + "x" + std::to_string(ref_h) + " px: " + why);
                }
            }
        }
    }
    if (missing == used)
        throw Error(reader_.folder() + ": none of the " + std::to_string(used) + " frames the filter would use exists (first: " +
                    first_missing + ")");
    if (missing)
        warnings_.push_back(reader_.folder() + ": " + std::to_string(missing) + " of " + std::to_string(used) +
                            " frames are missing and will be skipped (first: " + first_missing + ")");
    if (oblique)
        warnings_.push_back(reader_.folder() + ": " + std::to_string(oblique) + " of " + std::to_string(used) + " frames are tilted more than " +
                            number(max_tilt_deg_) + " deg from nadir (ImuX..W) and will be skipped (first: " + first_oblique + ")");
    if (odometry_off)
        warnings_.push_back(reader_.folder() + ": the odometry leaves the map on " + std::to_string(odometry_off) + " of " +
                            std::to_string(count) + " rows (first: " + first_odometry_off + ")");
    if (hint_ == 0) hint_ = used;
    if (!(rows.identity() == reader_.identity())) check_unchanged();  // replaced between the two reads
}

// simulate replaces a dataset by renaming a new folder over it: rows read from the old
// metadata.csv would be paired with the new frames (a clean run's 0.5 m error became 28 m).
void AirFlightSource::check_unchanged() const {
    if (!reader_.unchanged())
        throw Error(reader_.folder() + "/metadata.csv: the dataset was replaced or changed while it was read (another trnkit simulate "
                                       "writing it?); the frames no longer match the rows, run again when it is complete");
}

std::string AirFlightSource::position() const { return place(reader_, last_filename_); }

bool AirFlightSource::next(FlightSample& s) {
    sim::AirRecord r;
    while (reader_.next(r)) {
        const std::size_t row = row_++;
        if (row % stride_) continue;
        last_filename_ = r.filename;
        s.frame_index = row;
        s.time_s = std::isfinite(r.time_s) ? r.time_s : row / fps_;  // TimeS when the folder has it
        s.has_truth = std::isfinite(r.map_x) && std::isfinite(r.map_y);
        s.truth_x = r.map_x, s.truth_y = r.map_y;
        s.truth_yaw = sim::heading_from_quaternion(r.orientation);
        s.odometry_east_m = r.svo_m.x, s.odometry_north_m = r.svo_m.y;
        s.odometry_source = "folder";
        s.heading_rad = sim::heading_from_quaternion(r.imu);
        s.odometry_yaw_rad = s.heading_rad;  // the folder has no other heading: its changes turn a compass-less filter
        s.map_px_per_camera_px = sim::template_scale(camera_, r.relative_altitude_m, mpp_);
        s.image = {};
        s.image_error.clear();
        s.tilt_deg = tilt_deg(r);
        s.too_oblique = s.tilt_deg > max_tilt_deg_;
        if (s.too_oblique) {  // never scored at a wrong place and scale; counted by the caller
            s.image_error = position() + ": tilted " + number(s.tilt_deg) + " deg from nadir, more than " + number(max_tilt_deg_);
            return true;
        }
        ++attempted_;
        try {
            s.image = reader_.load_image(r);
        } catch (const Error& e) {
            s.image_error = e.what();  // counted by the filter as a missing frame
            if (first_load_error_.empty()) first_load_error_ = e.what();
        }
        if (!s.image.pixels.empty()) {
            // The scale of this frame's own pixels: the focal length in pixels grows with the width.
            const sim::Camera own{s.image.width, s.image.height, camera_.hfov_deg};
            try {
                s.map_px_per_camera_px = sim::template_scale(own, r.relative_altitude_m, mpp_);
            } catch (const Error& e) {
                throw Error(position() + ": " + e.what());
            }
            ++loaded_;
            const sim::RollPitch rp = sim::roll_pitch_from_quaternion(r.imu);
            LevelledFrame level = level_frame(s.image.view(), own.hfov_deg, rp.roll_rad, rp.pitch_rad, max_tilt_deg_);
            if (level.too_oblique) {  // no level view left (a generous max_tilt_deg)
                s.image = {};
                s.too_oblique = true;
                s.image_error = position() + ": " + level.error;
            } else if (!level.image.pixels.empty()) {
                s.image = std::move(level.image);
            }
        }
        return true;
    }
    check_unchanged();
    if (attempted_ > 0 && loaded_ == 0)
        throw Error(reader_.folder() + ": none of the " + std::to_string(attempted_) + " frames could be read (first: " +
                    first_load_error_ + ")");
    return false;
}

SimulatedFlightSource::SimulatedFlightSource(const sim::Map& world, const sim::FlightConfig& config, std::size_t stride)
    : world_(world),
      config_(config),
      simulator_(world, [&] {
          sim::FlightConfig c = config;
          c.render_images = false;  // rendered here, only for the frames the filter uses
          return c;
      }()),
      stride_(stride) {
    if (stride == 0) throw Error("SimulatedFlightSource: stride must be >= 1");
}

bool SimulatedFlightSource::next(FlightSample& s) {
    sim::FlightFrame f;
    while (simulator_.next(f)) {
        if (f.index % stride_) continue;
        s.frame_index = f.index;
        s.time_s = f.time_s;
        s.has_truth = true;
        s.truth_x = f.truth.map_x, s.truth_y = f.truth.map_y, s.truth_yaw = f.truth.yaw_rad;
        s.odometry_east_m = f.odometry_m.x, s.odometry_north_m = f.odometry_m.y;
        s.odometry_source = "simulated";
        s.heading_rad = f.magnetometer_heading_rad;
        s.odometry_yaw_rad = f.odometry_yaw_rad;
        s.map_px_per_camera_px = sim::measured_template_scale(f, config_.camera, world_.metres_per_pixel);  // barometric, like a real flight
        sim::RenderOptions r = config_.render;
        r.noise_seed = ((config_.seed * 0x9E3779B97F4A7C15ull) ^ (r.noise_seed + 0x632BE59BD9B4E019ull * (f.index + 1))) | 1;
        const sim::CameraPose pose{f.truth.map_x, f.truth.map_y, f.truth.altitude_m, f.truth.yaw_rad, f.truth.roll_rad, f.truth.pitch_rad};
        s.image = sim::render_frame(world_, config_.camera, pose, r);
        s.image_error.clear();
        return true;
    }
    return false;
}

std::size_t count_air_rows(const std::string& folder) {
    std::string text;
    try {  // a FIFO, a device or a huge file is reported by the AirReader that reads it next
        text = io::read_input_file(folder + "/metadata.csv", io::kMaxTableFileBytes, "metadata.csv");
    } catch (const Error&) {
        return 0;
    }
    std::size_t lines = 0;
    for (std::size_t at = 0; at < text.size();) {
        std::size_t end = text.find('\n', at);
        if (end == std::string::npos) end = text.size();
        if (end > at) ++lines;
        at = end + 1;
    }
    return lines ? lines - 1 : 0;
}

}  // namespace trn::filter
