#include "trn/sim/sensors.hpp"

#include <algorithm>
#include <cmath>

#include "random.hpp"
#include "trn/detail/angles.hpp"

namespace trn::sim {

OdometrySimulator::OdometrySimulator(const OdometryConfig& config)
    : config_(config),
      rng_(detail::mix64(config.seed ^ 0x0D0D0D0Dull)),
      heading_error_(config.heading_bias_deg * kDeg),
      scale_error_(config.scale_error) {}

Vec3 OdometrySimulator::step(const Vec3& d, double dt, double yaw_rate) {
    using detail::normal;
    const double turned = std::abs(yaw_rate) * dt;
    if (turned > 0) heading_error_ += config_.turn_heading_noise_deg_per_sqrt_rad * kDeg * std::sqrt(turned) * normal(rng_);
    // Drawn only when on, so a flight without them keeps its random sequence.
    const double root_dt = std::sqrt(std::max(dt, 0.0));
    if (config_.heading_walk_deg_per_sqrt_s > 0) heading_error_ += config_.heading_walk_deg_per_sqrt_s * kDeg * root_dt * normal(rng_);
    if (config_.scale_walk_per_sqrt_s > 0) scale_error_ += config_.scale_walk_per_sqrt_s * root_dt * normal(rng_);
    const double k = 1 + scale_error_;
    const double c = std::cos(heading_error_), s = std::sin(heading_error_);
    // East/north components; a positive heading error turns the track clockwise, like the heading.
    const double e = k * (c * d.x + s * d.y), n = k * (-s * d.x + c * d.y);
    const double walk =
        config_.random_walk_m_per_sqrt_s * std::sqrt(std::max(dt, 0.0)) * (1 + config_.turn_random_walk_gain_per_rad_s * std::abs(yaw_rate));
    estimate_.x += e + walk * normal(rng_);
    estimate_.y += n + walk * normal(rng_);
    estimate_.z += k * d.z + walk * normal(rng_);
    return estimate_;
}

Magnetometer::Magnetometer(const MagnetometerConfig& config) : config_(config), rng_(detail::mix64(config.seed ^ 0x3A6E7u)) {}

Barometer::Barometer(const BarometerConfig& config) : config_(config), rng_(detail::mix64(config.seed ^ 0xBA30ull)) {}

double Barometer::read(double true_altitude_m, double dt) {
    if (config_.bias_walk_m_per_sqrt_s > 0) bias_m_ += config_.bias_walk_m_per_sqrt_s * std::sqrt(std::max(dt, 0.0)) * detail::normal(rng_);
    const double white = config_.noise_m > 0 ? config_.noise_m * detail::normal(rng_) : 0;
    return true_altitude_m + bias_m_ + white;
}

double Magnetometer::read(double true_heading) {
    const double noise = std::clamp(config_.sigma_deg * detail::normal(rng_), -config_.bound_deg, config_.bound_deg);
    return wrap_angle(true_heading + noise * kDeg);
}

}  // namespace trn::sim
