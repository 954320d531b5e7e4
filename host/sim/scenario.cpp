#include "trn/sim/scenario.hpp"

#include <algorithm>
#include <cmath>

#include "trn/error.hpp"
#include "trn/sim/sensors.hpp"
#include "trn/detail/angles.hpp"

namespace trn::sim {
namespace {

constexpr double kTurnRadiusM = 40;  // U-turns of the line, corners of the rectangle

// Flight distances of the dissertation's AIR flights (Table 2.2), metres, in preset order
// (F/U x L/R/C x 200/300).
constexpr double kTable22DistanceM[12] = {2936, 2736, 4748, 4541, 1065, 1028, 2592, 2496, 4418, 4542, 1016, 970};

std::vector<Scenario> make_presets() {
    std::vector<Scenario> out;
    auto add_wind_twins = [&out] {
        const std::size_t n = out.size();
        for (std::size_t i = 0; i < n; ++i) {
            Scenario s = out[i];
            s.name += "-wind";
            s.realism = field_realism();
            out.push_back(s);
        }
    };
    for (TerrainStyle terrain : {TerrainStyle::Forest, TerrainStyle::Urban})
        for (TrajectoryShape shape : {TrajectoryShape::Line, TrajectoryShape::Rectangle, TrajectoryShape::Circle})
            for (double altitude : {200.0, 300.0}) {
                Scenario s;
                s.name = std::string(terrain == TerrainStyle::Forest ? "F" : "U") +
                         (shape == TrajectoryShape::Line ? "L" : shape == TrajectoryShape::Rectangle ? "R" : "C") + "-" +
                         std::to_string(static_cast<int>(altitude));
                s.terrain = terrain;
                s.shape = shape;
                s.altitude_m = altitude;
                s.nominal_size_m = shape == TrajectoryShape::Line ? 1600 : shape == TrajectoryShape::Rectangle ? 1100 : 1200;
                out.push_back(s);
            }
    add_wind_twins();
    // The -long twins of the 12 AIR presets: the dissertation's distance in one loop, with level
    // changes to the other altitude of the family (200 <-> 300 m).
    for (std::size_t i = 0; i < 12; ++i) {
        Scenario s = out[i];
        s.name += "-long";
        s.other_altitude_m = s.altitude_m == 200 ? 300 : 200;
        s.nominal_size_m = Trajectory::nominal_size_for_loop(s.shape, kTable22DistanceM[i]);
        s.duration_s = kTable22DistanceM[i] / s.speed_mps;
        s.one_loop = true;
        out.push_back(s);
    }
    return out;
}

// Appends an arc (centre, radius, from angle a0 to a1; angles of the point around the centre in
// map axes) sampled every ~1 m.
void arc(std::vector<double>& xs, std::vector<double>& ys, double cx, double cy, double r, double a0, double a1) {
    const int n = std::max(2, static_cast<int>(std::ceil(std::abs(a1 - a0) * r)));
    for (int i = 1; i <= n; ++i) {
        const double a = a0 + (a1 - a0) * i / n;
        xs.push_back(cx + r * std::cos(a));
        ys.push_back(cy + r * std::sin(a));
    }
}

void segment(std::vector<double>& xs, std::vector<double>& ys, double x1, double y1) {
    const double x0 = xs.back(), y0 = ys.back();
    const int n = std::max(1, static_cast<int>(std::ceil(std::hypot(x1 - x0, y1 - y0))));
    for (int i = 1; i <= n; ++i) {
        xs.push_back(x0 + (x1 - x0) * i / n);
        ys.push_back(y0 + (y1 - y0) * i / n);
    }
}

}  // namespace

Realism field_realism() {
    Realism r;
    r.crab_max_deg = 30;
    r.altitude_change = 0.3;
    r.baro_noise_m = 1.5;
    r.baro_bias_walk_m_per_sqrt_s = 0.1;
    r.odometry_heading_walk_deg_per_sqrt_s = 0.15;
    r.odometry_scale_walk_per_sqrt_s = 0.002;
    return r;
}

void Realism::validate() const {
    auto check = [](double v, double lo, double hi, const char* name) {
        if (!(v >= lo && v <= hi))
            throw Error(std::string("realism: ") + name + " " + std::to_string(v) + " must be in [" + std::to_string(lo) + ", " +
                        std::to_string(hi) + "]");
    };
    check(crab_max_deg, 0, 60, "crab_max_deg");
    check(mount_yaw_deg, -180, 180, "mount_yaw_deg");
    check(altitude_change, 0, 0.6, "altitude_change");
    check(baro_noise_m, 0, 100, "baro_noise_m");
    check(baro_bias_walk_m_per_sqrt_s, 0, 10, "baro_bias_walk_m_per_sqrt_s");
    check(odometry_heading_walk_deg_per_sqrt_s, 0, 10, "odometry_heading_walk_deg_per_sqrt_s");
    check(odometry_scale_walk_per_sqrt_s, 0, 0.1, "odometry_scale_walk_per_sqrt_s");
}

std::size_t Scenario::frame_count() const { return static_cast<std::size_t>(std::llround(duration_s * fps)); }

const std::vector<Scenario>& scenario_presets() {
    static const std::vector<Scenario> presets = make_presets();
    return presets;
}

const Scenario& find_scenario(std::string_view name) {
    std::string names;
    for (const Scenario& s : scenario_presets()) {
        if (s.name == name) return s;
        names += (names.empty() ? "" : ", ") + s.name;
    }
    throw Error("scenario '" + std::string(name) + "': unknown; expected one of " + names);
}

Trajectory::Trajectory(TrajectoryShape shape, double size, double speed, double min_x, double min_y, double max_x,
                       double max_y)
    : speed_(speed) {
    if (!(speed > 0)) throw Error("trajectory: speed " + std::to_string(speed) + " m/s must be > 0");
    if (!(max_x - min_x > 20 && max_y - min_y > 20))
        throw Error("trajectory: the usable area (" + std::to_string(max_x - min_x) + " x " + std::to_string(max_y - min_y) +
                    " m) is too small; the map must exceed the camera footprint by at least 20 m");
    // The loop at nominal size around (0, 0), flown clockwise on the map (y points south).
    std::vector<double> xs{0}, ys{0};
    const double turn = kTurnRadiusM;
    if (shape == TrajectoryShape::Circle) {
        xs = {size / 2}, ys = {0};
        arc(xs, ys, 0, 0, size / 2, 0, 2 * kPi);
    } else if (shape == TrajectoryShape::Rectangle) {
        const double a = size / 2, b = size * 0.35, r = turn;
        xs = {-a + r}, ys = {-b};
        segment(xs, ys, a - r, -b);
        arc(xs, ys, a - r, -b + r, r, -kPi / 2, 0);
        segment(xs, ys, a, b - r);
        arc(xs, ys, a - r, b - r, r, 0, kPi / 2);
        segment(xs, ys, -a + r, b);
        arc(xs, ys, -a + r, b - r, r, kPi / 2, kPi);
        segment(xs, ys, -a, -b + r);
        arc(xs, ys, -a + r, -b + r, r, kPi, 1.5 * kPi);
    } else {  // out along a line, U-turn, back on a parallel line, U-turn
        const double a = size / 2, r = turn;
        xs = {-a}, ys = {-r};
        segment(xs, ys, a, -r);
        arc(xs, ys, a, 0, r, -kPi / 2, kPi / 2);
        segment(xs, ys, -a, r);
        arc(xs, ys, -a, 0, r, kPi / 2, 1.5 * kPi);
    }
    // Rotate (a line / rectangle at an angle looks less like the map's road grid), then fit.
    const double rot = shape == TrajectoryShape::Circle ? 0 : 0.52;
    double bx0 = 1e300, by0 = 1e300, bx1 = -1e300, by1 = -1e300;
    for (std::size_t i = 0; i < xs.size(); ++i) {
        const double x = xs[i] * std::cos(rot) - ys[i] * std::sin(rot), y = xs[i] * std::sin(rot) + ys[i] * std::cos(rot);
        xs[i] = x, ys[i] = y;
        bx0 = std::min(bx0, x), bx1 = std::max(bx1, x), by0 = std::min(by0, y), by1 = std::max(by1, y);
    }
    const double fit = std::min({1.0, (max_x - min_x) / (bx1 - bx0), (max_y - min_y) / (by1 - by0)});
    const double cx = (min_x + max_x) / 2, cy = (min_y + max_y) / 2, ox = (bx0 + bx1) / 2, oy = (by0 + by1) / 2;
    cumulative_.assign(xs.size(), 0);
    for (std::size_t i = 0; i < xs.size(); ++i) {
        xs[i] = cx + (xs[i] - ox) * fit, ys[i] = cy + (ys[i] - oy) * fit;
        if (i) cumulative_[i] = cumulative_[i - 1] + std::hypot(xs[i] - xs[i - 1], ys[i] - ys[i - 1]);
    }
    xs_ = std::move(xs), ys_ = std::move(ys);
}

double Trajectory::nominal_size_for_loop(TrajectoryShape shape, double length) {
    // Inverts the loop lengths of the constructor: circle pi*d; line out and back 2*size plus two
    // half turns; rectangle size x 0.7 size with four rounded corners.
    const double r = kTurnRadiusM;
    if (shape == TrajectoryShape::Circle) return length / kPi;
    if (shape == TrajectoryShape::Line) return (length - 2 * kPi * r) / 2;
    return (length + (8 - 2 * kPi) * r) / 3.4;
}

void Trajectory::sample(double s, double& x, double& y) const {
    const double total = cumulative_.back();
    s = std::fmod(s, total);
    if (s < 0) s += total;
    const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), s);
    const std::size_t i = std::clamp<std::size_t>(static_cast<std::size_t>(it - cumulative_.begin()), 1, cumulative_.size() - 1);
    const double len = cumulative_[i] - cumulative_[i - 1];
    const double t = len > 0 ? (s - cumulative_[i - 1]) / len : 0;
    x = xs_[i - 1] + t * (xs_[i] - xs_[i - 1]);
    y = ys_[i - 1] + t * (ys_[i] - ys_[i - 1]);
}

double Trajectory::heading_at(double s) const {
    double x0, y0, x1, y1;
    sample(s - 2, x0, y0);
    sample(s + 2, x1, y1);
    return std::atan2(x1 - x0, -(y1 - y0));  // compass: 0 north (-y), pi/2 east (+x)
}

TrajectoryState Trajectory::at(double t) const {
    const double s = speed_ * t;
    TrajectoryState st;
    sample(s, st.x_m, st.y_m);
    st.heading_rad = heading_at(s);
    const double ds = 3;
    st.yaw_rate_rad_s = wrap_angle(heading_at(s + ds) - heading_at(s - ds)) / (2 * ds) * speed_;
    return st;
}

}  // namespace trn::sim
