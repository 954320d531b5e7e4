#pragma once
// A simulated flight as a stream of frames with ground truth and sensor readings, generated in
// memory on demand (write it out with air_format.hpp, or feed it straight to a filter).
#include <cstddef>
#include <cstdint>

#include "trn/scoring.hpp"
#include "trn/sim/altitude_profile.hpp"
#include "trn/sim/camera.hpp"
#include "trn/sim/field_conditions.hpp"
#include "trn/sim/map.hpp"
#include "trn/sim/render.hpp"
#include "trn/sim/scenario.hpp"
#include "trn/sim/sensors.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::sim {

struct GroundTruth {
    double map_x = 0, map_y = 0;  // map pixel under the aircraft
    double yaw_rad = 0;           // compass heading of the frame top (scoring.hpp convention)
    double course_rad = 0;        // compass direction of travel (= yaw_rad without wind or mount yaw)
    double altitude_m = 0;        // above ground
    double roll_rad = 0, pitch_rad = 0;  // camera attitude (0 with the gimbal)
};

struct FlightFrame {
    std::size_t index = 0;
    double time_s = 0;
    GroundTruth truth;
    Vec3 position_m;               // true east / north / up from the start point
    LatLon geo;                    // true latitude / longitude
    Vec3 odometry_m;               // visual odometry estimate, same frame as position_m
    double odometry_yaw_rad = 0;   // the odometry's own yaw of the frame top in that frame: truth + its heading error
    double magnetometer_heading_rad = 0;  // measured heading of the camera (frame top)
    double baro_altitude_m = 0;    // measured altitude above ground (barometer)
    double template_scale = 1;     // map pixels per camera pixel at the TRUE altitude (truth_pose)
    GrayImage image;               // empty when the flight is not rendering images

    // The pose to score this frame at on the map: the truth as a scoring Pose.
    Pose truth_pose() const;
};

// Map pixels per camera pixel as a localizer would compute it: from the barometric altitude.
double measured_template_scale(const FlightFrame& frame, const Camera& camera, double metres_per_pixel);

struct FlightConfig {
    Scenario scenario;
    Camera camera;
    RenderOptions render;
    OdometryConfig odometry;
    MagnetometerConfig magnetometer;
    double camera_roll_pitch_sd_deg = 0;  // 0: gimbal-stabilised; else random slow wobble
    std::size_t frames = 0;               // 0: the scenario's full duration
    bool render_images = true;
    std::uint64_t seed = 1;               // seeds noise, odometry, magnetometer and wobble
};

// Edge (metres) of a square procedural map that holds the flight: the scenario's loop at nominal
// size plus the camera footprint at its highest altitude. A one_loop ("-long") preset's loop is
// measured so that it is never shrunk; the others keep the studies' 1.1 x nominal size rule.
double fitting_map_edge_m(const FlightConfig& config);

class FlightSimulator {
public:
    // Renders from `map` (keep it alive while simulating). Throws trn::Error when the map is too
    // small for the camera footprint at the scenario's altitude.
    FlightSimulator(const Map& map, const FlightConfig& config);

    std::size_t frame_count() const { return frame_count_; }
    // Fills the next frame; false when the flight is over.
    bool next(FlightFrame& frame);
    const Trajectory& trajectory() const { return trajectory_; }
    const FlightConfig& config() const { return config_; }

private:
    double altitude_m(double time_s) const;  // level changes plus the realism's swings

    const Map& map_;
    FlightConfig config_;
    Trajectory trajectory_;
    std::size_t frame_count_;
    std::size_t next_index_ = 0;
    OdometrySimulator odometry_;
    Magnetometer magnetometer_;
    Barometer barometer_;
    FieldConditions conditions_;
    AltitudeProfile profile_;
    TrajectoryState previous_;
    double previous_altitude_m_ = 0;
    double start_x_m_ = 0, start_y_m_ = 0;
};

}  // namespace trn::sim
TRN_API_END
