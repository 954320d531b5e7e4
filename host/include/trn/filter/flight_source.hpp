#pragma once
// Where the localizer gets its frames: a recorded AIR flight folder or a flight simulated in memory.
// Both give the same samples (sensors + optional ground truth + the camera image), every
// `stride`-th frame, so the filter can run at a lower rate than the camera.
#include <cmath>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "trn/io/image_io.hpp"
#include "trn/sim/air_format.hpp"
#include "trn/sim/flight.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::filter {

struct FlightSample {
    std::size_t frame_index = 0;
    double time_s = 0;
    bool has_truth = false;
    double truth_x = 0, truth_y = 0, truth_yaw = 0;     // map pixels, radians
    double odometry_east_m = 0, odometry_north_m = 0;    // visual odometry, from the start (NaN: lost)
    double heading_rad = 0;                              // magnetometer / IMU heading (NaN: none)
    // The odometry's own yaw of the frame top, in the frame of odometry_east/north_m (clockwise,
    // radians; NaN: none). Only its changes matter (compass-less localization): an AIR folder's is
    // its ImuX..W heading, the simulator's the odometry's (truth + its heading error), visual
    // odometry's the sum of the rotations it measured (visual_odometry.hpp).
    double odometry_yaw_rad = NAN;
    double map_px_per_camera_px = 1;                     // of `image` as returned (its own width)
    double tilt_deg = 0;                                 // optical axis from the vertical (measured roll/pitch)
    bool too_oblique = false;                            // tilt beyond the limit: not loaded, not scored
    GrayImage image;                                     // empty when it failed to load or is too oblique
    std::string image_error;                             // why it is empty
    std::string odometry_source;                         // "simulated", "folder", "visual:..." (visual_odometry.hpp)
};

class FlightSource {
public:
    virtual ~FlightSource() = default;
    virtual bool next(FlightSample& sample) = 0;
    virtual std::size_t frames_hint() const = 0;  // expected samples (0: unknown)
};

// The localization map's size in pixels; 0 x 0 when unknown (coverage is then not checked).
struct MapExtent {
    int width = 0, height = 0;
};

// An AIR folder (the camera's field of view from flight.json or the command line; the map
// resolution is the localization map's). The constructor reads every row first, so a folder the
// filter cannot use fails at once with file:line: no rows, an altitude that is no flight's, ground
// truth off the map, every frame missing. What a run survives (a few frames missing, odometry
// drifting off the map, frames too oblique) becomes warnings().
// Each frame's scale comes from its own width (focal length = width/2 / tan(hfov/2)), so frames of
// differing sizes are each scored at their own scale, as long as each is the same view at another
// resolution: a frame whose aspect ratio differs from the camera's (`camera_size_stated`, i.e. the
// size flight.json states) or, without one, from the first frame's (a crop, a rotated frame, another
// camera) is refused before the run, naming the file and both sizes (frame_size_problem). Roll and pitch are read from ImuX..W: a
// tilted frame is warped to nadir (nadir_warp.hpp); one tilted more than max_tilt_deg is not
// loaded and comes back empty with too_oblique set.
class AirFlightSource : public FlightSource {
public:
    AirFlightSource(const std::string& folder, const sim::Camera& camera, double metres_per_pixel, double fps,
                    std::size_t stride, std::size_t frames_hint = 0, MapExtent map = {}, double max_tilt_deg = 10,
                    bool camera_size_stated = false);
    bool next(FlightSample& sample) override;
    std::size_t frames_hint() const override { return hint_; }
    const std::vector<std::string>& warnings() const { return warnings_; }
    // "folder/metadata.csv:LINE (FILENAME)" of the sample last returned, to give errors a place.
    std::string position() const;
    // Throws trn::Error naming metadata.csv when the file at its path is no longer the one read
    // (the dataset was replaced or rewritten meanwhile); next() calls it when the rows end.
    void check_unchanged() const;

private:
    void check_rows(MapExtent map);

    sim::AirReader reader_;
    sim::Camera camera_;
    bool camera_size_stated_ = false;
    double mpp_, fps_, max_tilt_deg_;
    std::size_t stride_, row_ = 0, hint_, loaded_ = 0, attempted_ = 0;
    std::string last_filename_, first_load_error_;
    std::vector<std::string> warnings_;
};

// A flight simulated over `world` (kept alive by the caller): renders only the frames it returns.
class SimulatedFlightSource : public FlightSource {
public:
    SimulatedFlightSource(const sim::Map& world, const sim::FlightConfig& config, std::size_t stride);
    bool next(FlightSample& sample) override;
    std::size_t frames_hint() const override { return (simulator_.frame_count() + stride_ - 1) / stride_; }

private:
    const sim::Map& world_;
    sim::FlightConfig config_;
    sim::FlightSimulator simulator_;
    std::size_t stride_;
};

// Why a frame of `width` x `height` px cannot be scored as a view of a camera (or first frame) of
// `ref_width` x `ref_height` px, "" when it can: the same view at another resolution keeps the
// aspect ratio, so its height is the reference's scaled by the width ratio within 1 px or 1 %
// (rounding when a frame was resized). Another aspect ratio is another view, whose focal length
// in pixels the width no longer gives.
std::string frame_size_problem(int width, int height, int ref_width, int ref_height);

// Counts the rows of an AIR folder's metadata.csv (for a progress bar).
std::size_t count_air_rows(const std::string& folder);

}  // namespace trn::filter
TRN_API_END
