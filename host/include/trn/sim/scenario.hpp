#pragma once
// The twelve AIR flight presets and their trajectories.
//
// Names follow the dataset: terrain (F forest, U urban) + shape (L line, R rectangle, C circle)
// + altitude, e.g. "FL-200", "UC-300". A trajectory is a closed loop flown at constant speed and
// altitude (a line is flown out and back with U-turns), fitted into the area it is given, so the
// same preset works on a 6 km procedural map and on a 900 m orthophoto.
#include <string>
#include <string_view>
#include <vector>

#include "trn/sim/procedural_map.hpp"

namespace trn::sim {

enum class TrajectoryShape { Line, Rectangle, Circle };

struct Scenario {
    std::string name;
    TerrainStyle terrain = TerrainStyle::Forest;
    TrajectoryShape shape = TrajectoryShape::Line;
    double altitude_m = 200;
    double speed_mps = 12;
    double fps = 50;
    double duration_s = 320;  // 16,000 frames at 50 FPS, as a real AIR flight
    double nominal_size_m = 1600;  // line length / rectangle long side / circle diameter

    std::size_t frame_count() const;
};

const std::vector<Scenario>& scenario_presets();
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
    double loop_length_m() const { return cumulative_.back(); }

private:
    void sample(double s, double& x, double& y) const;
    double heading_at(double s) const;
    std::vector<double> xs_, ys_, cumulative_;
    double speed_;
};

}  // namespace trn::sim
