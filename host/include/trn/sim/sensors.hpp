#pragma once
// Simulated navigation sensors. Each one is seeded, so a run is reproducible.
#include <cstdint>
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::sim {

struct Vec3 {
    double x = 0, y = 0, z = 0;
};

// Visual odometry (SVO-like) drift model. The estimate integrates the true displacement of each
// step in a local east/north/up frame starting at 0, distorted by
//   - a scale error: distances come out (1 + scale_error) times the truth,
//   - a constant heading bias that rotates the estimated track,
//   - a position random walk (white velocity noise), and
//   - extra error in turns: each radian turned adds a random heading error (sd per sqrt(radian))
//     and the random walk grows with the turn rate, as SVO loses accuracy in turns,
//   - optionally (0 by default) a slow random walk of its direction and of its scale, so that
//     the odometry's course drifts away from the true course even on straight legs.
struct OdometryConfig {
    double scale_error = 0.03;
    double heading_bias_deg = 1.0;
    double random_walk_m_per_sqrt_s = 0.05;
    double turn_heading_noise_deg_per_sqrt_rad = 2.0;
    double turn_random_walk_gain_per_rad_s = 5.0;  // random walk x (1 + gain * |yaw rate|)
    double heading_walk_deg_per_sqrt_s = 0;        // direction random walk
    double scale_walk_per_sqrt_s = 0;              // scale-error random walk
    std::uint64_t seed = 1;
};

class OdometrySimulator {
public:
    explicit OdometrySimulator(const OdometryConfig& config);
    // One step: true displacement (east, north, up metres) over dt seconds at this yaw rate.
    // Returns the new estimate of the position relative to the start.
    Vec3 step(const Vec3& true_delta, double dt_s, double yaw_rate_rad_s);
    const Vec3& estimate() const { return estimate_; }
    double heading_error_rad() const { return heading_error_; }  // bias + accumulated turn error and walk
    double scale_error() const { return scale_error_; }

private:
    OdometryConfig config_;
    std::uint64_t rng_;
    Vec3 estimate_;
    double heading_error_;
    double scale_error_;
};

// Magnetometer heading: truth + Gaussian noise, clipped to +-bound (the +-2 degree sensor spec).
struct MagnetometerConfig {
    double sigma_deg = 1.0;
    double bound_deg = 2.0;
    std::uint64_t seed = 2;
};

class Magnetometer {
public:
    explicit Magnetometer(const MagnetometerConfig& config);
    double read(double true_heading_rad);  // radians, wrapped to (-pi, pi]

private:
    MagnetometerConfig config_;
    std::uint64_t rng_;
};

// Barometric altitude: truth + white noise + a bias that random-walks from 0.
struct BarometerConfig {
    double noise_m = 0;
    double bias_walk_m_per_sqrt_s = 0;
    std::uint64_t seed = 3;
};

class Barometer {
public:
    explicit Barometer(const BarometerConfig& config);
    double read(double true_altitude_m, double dt_s);  // dt_s: time since the previous reading

private:
    BarometerConfig config_;
    std::uint64_t rng_;
    double bias_m_ = 0;
};

}  // namespace trn::sim
TRN_API_END
