#pragma once
// The twelve AIR flight presets, their twelve "-wind" twins and the trajectories.
//
// Names follow the dataset: terrain (F forest, U urban) + shape (L line, R rectangle, C circle)
// + altitude, e.g. "FL-200", "UC-300". A trajectory is a closed loop flown at constant speed
// (a line is flown out and back with U-turns), fitted into the area it is given, so the same
// preset works on a 6 km procedural map and on a 900 m orthophoto.
//
// The AIR presets are the dataset's idealised world: the camera points along the track, the
// altitude is constant and known. Each has a twin "<name>-wind" (e.g. "FR-200-wind") with
// field_realism() on: wind crab, climbs and descents, a noisy barometer, drifting odometry.
// And a twin "<name>-long" (e.g. "FR-200-long") that flies the dissertation's distance of that
// scenario (Table 2.2: 0.97-4.75 km) as one whole loop, climbing and descending between the
// family's two altitudes, 200 and 300 m (altitude_profile.hpp); otherwise the AIR world.
#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include "trn/sim/procedural_map.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::sim {

enum class TrajectoryShape { Line, Rectangle, Circle };

// What real flights have and the AIR presets do not (all zero = the AIR dataset's world).
struct Realism {
    // Wind: the camera heading is the course plus a crab angle, asin(wind/airspeed * sin(wind
    // direction - course)), with wind/airspeed = sin(crab_max_deg); the wind direction starts
    // 45-135 degrees off the first course and veers slowly (+-40 degrees), gusts add +-20 %.
    double crab_max_deg = 0;
    double mount_yaw_deg = 0;           // constant yaw of the camera mount against the airframe
    // Climbs / descents: altitude = nominal * (1 + altitude_change * p(t)), p a smooth seeded
    // profile in [-1, 1] (periods of 70-200 s, so at 12 m/s a full swing takes ~0.5-1 km).
    double altitude_change = 0;
    // Barometric altitude (what RelativeAltitude records and the filter scales templates by):
    // truth + white noise (sd) + a bias random walk (m per sqrt(s)).
    double baro_noise_m = 0;
    double baro_bias_walk_m_per_sqrt_s = 0;
    // Extra odometry drift on top of FlightConfig::odometry: its direction and its scale random-walk.
    double odometry_heading_walk_deg_per_sqrt_s = 0;
    double odometry_scale_walk_per_sqrt_s = 0;

    void validate() const;  // throws trn::Error naming the field
};

// The "-wind" presets' realism: crab up to 30 degrees, +-30 % altitude, barometer 1.5 m sd with a
// 0.1 m/sqrt(s) bias walk, odometry direction walk 0.15 deg/sqrt(s), scale walk 0.002/sqrt(s).
Realism field_realism();

struct Scenario {
    std::string name;
    TerrainStyle terrain = TerrainStyle::Forest;
    TrajectoryShape shape = TrajectoryShape::Line;
    double altitude_m = 200;
    double speed_mps = 12;
    double fps = 50;
    double duration_s = 320;  // 16,000 frames at 50 FPS, as a real AIR flight
    double nominal_size_m = 1600;  // line length / rectangle long side / circle diameter
    Realism realism;               // all zero for the AIR presets
    // Level changes ("-long" presets): level legs alternate between altitude_m and this altitude
    // (0: none), joined by climbs / descents of climb_s seconds (altitude_profile.hpp).
    double other_altitude_m = 0;
    double climb_s = 40;
    // "-long" presets: the flight is one whole loop at nominal size (maps are sized so that it is
    // not shrunk: fitting_map_edge_m in flight.hpp), so its length is distance_m().
    bool one_loop = false;

    // Highest altitude the flight reaches (the camera footprint must fit the map up there).
    double max_altitude_m() const { return std::max(altitude_m, other_altitude_m) * (1 + realism.altitude_change); }
    double distance_m() const { return speed_mps * duration_s; }

    std::size_t frame_count() const;
};

const std::vector<Scenario>& scenario_presets();  // the 12 AIR presets, then the -wind, then the -long twins
// Throws trn::Error listing the valid names when `name` is not one.
const Scenario& find_scenario(std::string_view name);

// Where the aircraft is at time t. x, y in metres from the map's top-left corner (east, south);
// heading is the compass heading of travel (0 north, pi/2 east); yaw_rate in rad/s (+ clockwise).
struct TrajectoryState {
    double x_m = 0, y_m = 0;
    double heading_rad = 0;
    double yaw_rate_rad_s = 0;
};

class Trajectory {
public:
    // Fits the shape into [min_x, max_x] x [min_y, max_y] (metres), centred, shrunk when needed.
    Trajectory(TrajectoryShape shape, double nominal_size_m, double speed_mps, double min_x, double min_y,
               double max_x, double max_y);
    TrajectoryState at(double time_s) const;
    // The nominal size whose loop (at full size) is `loop_length_m` long.
    static double nominal_size_for_loop(TrajectoryShape shape, double loop_length_m);
    double loop_length_m() const { return cumulative_.back(); }

private:
    void sample(double s, double& x, double& y) const;
    double heading_at(double s) const;
    std::vector<double> xs_, ys_, cumulative_;
    double speed_;
};

}  // namespace trn::sim
TRN_API_END
