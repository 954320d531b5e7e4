#include "trn/filter/lock_monitor.hpp"

#include <algorithm>
#include <string>

#include "trn/detail/splitmix.hpp"
#include "trn/error.hpp"
#include "trn/detail/angles.hpp"

namespace trn::filter {

void LockMonitorConfig::validate() const {
    auto in_range = [](double v, double lo, double hi, const char* name) {
        if (!(v >= lo && v <= hi))
            throw Error(std::string("lock monitor: ") + name + " " + std::to_string(v) + " must be finite and in [" +
                        std::to_string(lo) + ", " + std::to_string(hi) + "]");
    };
    in_range(static_cast<double>(probes), 0, 10000, "probes");
    in_range(probe_min_m, 0, 1e5, "probe_min_m");
    in_range(probe_max_m, probe_min_m, 1e5, "probe_max_m");
    in_range(min_contrast, 0, 100, "min_contrast");
    in_range(confident_contrast, min_contrast, 100, "confident_contrast");
    in_range(converged_m, 0, 1e5, "converged_m");
    in_range(fix_far_contrast, 0, 100, "fix_far_contrast");
    in_range(static_cast<double>(fix_steps), 1, 1e6, "fix_steps");
    in_range(static_cast<double>(weak_steps), 1, 1e6, "weak_steps");
    in_range(drift_fraction, 0, 10, "drift_fraction");
    in_range(drift_floor_m, 0, 1e5, "drift_floor_m");
    in_range(widen_fraction, 0, 1, "widen_fraction");
    in_range(widen_radius_m, 0, 1e5, "widen_radius_m");
    in_range(static_cast<double>(cooldown_steps), 0, 1e6, "cooldown_steps");
}

LockMonitor::LockMonitor(const LockMonitorConfig& config, double metres_per_pixel, std::uint64_t seed)
    : config_(config), mpp_(metres_per_pixel), rng_(splitmix::mix64(seed ^ 0x10C4ull)), near_rng_(splitmix::mix64(seed ^ 0x4EA2ull)) {
    config_.validate();
}

double LockMonitor::uniform() { return splitmix::uniform(rng_); }

void LockMonitor::reset(double x, double y, double uncertainty_m) {
    dead_x_ = x, dead_y_ = y;
    since_fix_m_ = 0;
    fix_uncertainty_m_ = uncertainty_m;
    weak_run_ = cooldown_ = candidate_run_ = 0;
    fixed_ = false;
}

void LockMonitor::predict(double dx, double dy) {
    if (!std::isfinite(dx) || !std::isfinite(dy)) return;
    dead_x_ += dx, dead_y_ += dy;
    candidate_x_ += dx, candidate_y_ += dy;
    since_fix_m_ += std::hypot(dx, dy) * mpp_;
}

std::size_t LockMonitor::add_probes(double x, double y, double yaw, std::vector<Pose>& poses) {
    if (!config_.enabled) return 0;
    const double r0 = config_.probe_min_m / mpp_, r1 = config_.probe_max_m / mpp_;
    for (std::size_t i = 0; i < config_.probes; ++i) {
        const double r = std::sqrt(r0 * r0 + (r1 * r1 - r0 * r0) * uniform()), a = 2 * kPi * uniform();  // uniform over the ring
        poses.push_back({static_cast<float>(x + r * std::cos(a)), static_cast<float>(y + r * std::sin(a)), static_cast<float>(yaw), 1.0f});
    }
    return config_.probes;
}

std::size_t LockMonitor::add_near_probes(double x, double y, double yaw, double footprint_px, int map_width, int map_height,
                                         std::vector<Pose>& poses) {
    if (!config_.enabled || map_width < 2 || map_height < 2 || !(footprint_px >= 0)) return 0;
    const double r_max = config_.probe_max_m / mpp_;
    std::size_t added = 0;
    // Uniform over the map, kept when in the annulus: a bounded number of tries, so a map with no
    // place far enough from the estimate gives fewer probes (or none), never a hang.
    for (std::size_t tries = 0; tries < 50 * config_.probes && added < config_.probes; ++tries) {
        const double px = splitmix::uniform(near_rng_) * (map_width - 1), py = splitmix::uniform(near_rng_) * (map_height - 1);
        const double r = std::hypot(px - x, py - y);
        if (r < footprint_px || r > r_max) continue;
        poses.push_back({static_cast<float>(px), static_cast<float>(py), static_cast<float>(yaw), 1.0f});
        ++added;
    }
    return added;
}

LockReport LockMonitor::assess(double best_ncc, std::span<const ParticleScore> probe_scores, double ex, double ey,
                               double spread_m) {
    LockReport r;
    if (!config_.enabled) return r;
    r.best_ncc = best_ncc;
    double n = 0, sum = 0, sum2 = 0;
    for (const ParticleScore& s : probe_scores)
        if (s.valid()) n += 1, sum += s.ncc, sum2 += double(s.ncc) * s.ncc;
    if (n >= kMinProbes && std::isfinite(best_ncc)) {  // too few probes on the map: no contrast evidence
        r.probe_mean = sum / n;
        r.probe_sd = std::sqrt(std::max(sum2 / n - r.probe_mean * r.probe_mean, 1e-6));
        r.contrast = (best_ncc - r.probe_mean) / r.probe_sd;
        r.weak = r.contrast < config_.min_contrast;
    }
    const bool converged = spread_m <= config_.converged_m;
    r.drift_m = std::hypot(ex - dead_x_, ey - dead_y_) * mpp_;
    r.drift_bound_m = fix_uncertainty_m_ + config_.drift_floor_m + config_.drift_fraction * since_fix_m_;
    r.inconsistent = converged && r.drift_m > r.drift_bound_m;
    weak_run_ = r.weak ? weak_run_ + 1 : 0;
    // A fix candidate: contrast enough for its distance from dead reckoning (lock_monitor.hpp).
    const double far = r.drift_bound_m > 0 ? r.drift_m / r.drift_bound_m : (r.drift_m > 0 ? INFINITY : 0);
    r.fix_contrast = config_.confident_contrast + config_.fix_far_contrast * far;
    const bool candidate = converged && r.contrast >= r.fix_contrast;
    const bool same_track = candidate_run_ > 0 && std::hypot(ex - candidate_x_, ey - candidate_y_) * mpp_ <= config_.converged_m;
    candidate_run_ = !candidate ? 0 : same_track ? candidate_run_ + 1 : 1;
    candidate_x_ = ex, candidate_y_ = ey;
    r.fix_run = candidate_run_;
    r.confident = candidate_run_ >= config_.fix_steps;
    if (r.confident) fixed_ = true;
    else if (r.weak) fixed_ = false;  // the place no longer stood out: the old fix vouches for nothing now
    r.fixed_before = fixed_;
    if (r.confident) {  // a fix: dead reckoning restarts here
        dead_x_ = ex, dead_y_ = ey;
        since_fix_m_ = 0;
        fix_uncertainty_m_ = 0;
        weak_run_ = 0;
        return r;
    }
    if (cooldown_ > 0) {
        --cooldown_;
        return r;  // the widened search is still settling: no verdict
    }
    if (candidate) return r;  // strong evidence still being confirmed: no verdict either way
    if (r.inconsistent || weak_run_ >= config_.weak_steps) {
        r.lost = true;
        fixed_ = r.fixed_before = false;  // judged again from here
        r.widen_radius_m = std::min(config_.widen_radius_m, r.drift_bound_m);
        weak_run_ = 0;
        cooldown_ = config_.cooldown_steps;
    }
    return r;
}

}  // namespace trn::filter
