#pragma once
// A recorded AIR folder read as a robot's sensors would feed the Localizer: per row the camera frame
// as taken (not levelled), the height above ground, the attitude, the compass heading and the
// odometry increment since the previous row, with the ground truth beside them. `trnkit localize`
// reads the same rows (filter::AirFlightSource), so a caller stepping a Localizer with
// observation() gets its estimates bit for bit (every row a step, the start at the first truth).
#include <cmath>
#include <cstddef>
#include <string>

#include "trn/io/image_io.hpp"
#include "trn/localize/localizer.hpp"
#include "trn/sim/air_format.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::localize {

// Odometry read from the start (a dataset's SvoX/SvoY) as increments since the previous reading;
// the first finite reading is the origin (increment 0), a non-finite one is lost (NaN).
class OdometryIncrements {
public:
    struct Step {
        double east_m = NAN, north_m = NAN;
    };
    Step next(double east_m, double north_m);
    double origin_east_m() const { return e0_; }
    double origin_north_m() const { return n0_; }
    double last_east_m() const { return prev_e_; }
    double last_north_m() const { return prev_n_; }

private:
    bool started_ = false;
    double e0_ = 0, n0_ = 0, prev_e_ = 0, prev_n_ = 0;
};

// Without a compass the Localizer takes each odometry step in the previous frame's axes and the
// frame's rotation since then (Observation::odometry_yaw_rad). A recorded odometry is a track in
// its own frame with its own yaw of the frame top (an AIR folder's ImuX..W heading, the
// simulator's odometry yaw, visual odometry's summed rotations): this turns each step (an
// OdometryIncrements step) by the yaw at the previous reading, and the rotation is the change of
// yaw. Only the yaw's changes enter, never its offset from north. A lost step (NaN) or one without
// a yaw gives NaN rotation; the first reading is the start (rotation 0).
class CompasslessOdometry {
public:
    struct Step {
        double right_m = NAN, forward_m = NAN, rotation_rad = NAN;
    };
    Step next(const OdometryIncrements::Step& step, double odometry_yaw_rad);

private:
    bool started_ = false;
    double yaw_ = NAN;  // at the last finite reading
};

struct AirFrame {
    std::size_t row = 0;                       // 0-based row of metadata.csv
    std::string filename;
    GrayImage image;                           // empty when it failed to load (image_error says why)
    std::string image_error;
    double altitude_agl_m = NAN;               // RelativeAltitude
    double heading_rad = NAN;                  // from ImuX..W
    double roll_rad = 0, pitch_rad = 0;        // from ImuX..W
    double odometry_east_m = NAN, odometry_north_m = NAN;  // SvoX/SvoY as read, from the start
    OdometryIncrements::Step odometry_step;    // since the previous row
    CompasslessOdometry::Step compassless_step;  // the same in the previous frame's axes, and the heading's change
    double truth_x = NAN, truth_y = NAN;       // MapX/MapY (NaN: none)
    double time_s = NAN;                       // TimeS (NaN: the folder has none)

    // The Localizer's input for this row (the frame view refers to `image`).
    Observation observation() const;
    // The same for a Localizer without a compass (filter.heading = HeadingMode::None): no heading,
    // the odometry in the previous frame's axes and the rotation from the ImuX..W heading's change.
    Observation observation_without_compass() const;
};

class AirFrameReader {
public:
    explicit AirFrameReader(const std::string& folder);
    bool next(AirFrame& frame);
    // "folder/metadata.csv:LINE" of the row last returned.
    std::string position() const;

private:
    sim::AirReader reader_;
    OdometryIncrements odometry_;
    CompasslessOdometry compassless_;
    std::size_t row_ = 0;
};

}  // namespace trn::localize
TRN_API_END
