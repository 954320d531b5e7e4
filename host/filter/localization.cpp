#include "trn/filter/localization.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "trn/error.hpp"

namespace trn::filter {

FittedLine fit_line(const std::vector<double>& x, const std::vector<double>& y) {
    const std::size_t n = x.size();
    if (n < 2 || y.size() != n) return {};
    double mx = 0, my = 0;
    for (std::size_t i = 0; i < n; ++i) mx += x[i], my += y[i];
    mx /= n, my /= n;
    double sxy = 0, sxx = 0;
    for (std::size_t i = 0; i < n; ++i) sxy += (x[i] - mx) * (y[i] - my), sxx += (x[i] - mx) * (x[i] - mx);
    if (!(sxx > 0)) return {};
    const double slope = sxy / sxx;
    return {slope, my - slope * mx};
}

std::map<std::string, double> with_lock_numbers(const LocalizationSummary& s, std::map<std::string, double> numbers) {
    numbers["lock_lost_events"] = static_cast<double>(s.counters.lock_lost_events);
    numbers["weak_contrast_steps"] = static_cast<double>(s.counters.weak_contrast_steps);
    numbers["odometry_inconsistent_steps"] = static_cast<double>(s.counters.odometry_inconsistent_steps);
    return numbers;
}

std::string format_lock_summary(const LocalizationSummary& s) {
    char buf[256];
    std::snprintf(buf, sizeof buf, "lock monitor: %zu lost (search widened), %zu weak-contrast steps, %zu odometry-inconsistent steps\n",
                  s.counters.lock_lost_events, s.counters.weak_contrast_steps, s.counters.odometry_inconsistent_steps);
    return buf;
}

LocalizationSummary summarise(const std::vector<LocalizationRow>& rows, const FilterCounters& counters, double wall_s) {
    LocalizationSummary s;
    s.steps = rows.size();
    s.counters = counters;
    if (rows.empty()) return s;
    // The filter sees a too-oblique frame as an empty one; missing means failed to load.
    for (const LocalizationRow& r : rows) s.counters.frames_missing -= r.too_oblique && s.counters.frames_missing > 0;
    std::vector<double> km, fe, oe;
    double particles = 0, score = 0;
    for (const LocalizationRow& r : rows) {
        particles += r.particles, score += r.score_ms;
        s.frames_too_oblique += r.too_oblique;
        if (std::isfinite(r.error_m) && std::isfinite(r.odometry_error_m)) {
            km.push_back(r.distance_m / 1000), fe.push_back(r.error_m), oe.push_back(r.odometry_error_m);
        }
    }
    s.mean_particles = particles / rows.size();
    s.mean_score_ms = score / rows.size();
    s.distance_m = rows.back().distance_m;
    s.frames_per_second = wall_s > 0 ? rows.size() / wall_s : 0;
    if (!fe.empty()) {
        double sf = 0, so = 0;
        for (std::size_t i = 0; i < fe.size(); ++i) sf += fe[i], so += oe[i];
        s.filter_mean_error_m = sf / fe.size(), s.odometry_mean_error_m = so / oe.size();
        s.filter_final_error_m = fe.back(), s.odometry_final_error_m = oe.back();
        const FittedLine f = fit_line(km, fe), o = fit_line(km, oe);
        s.filter_error_slope_m_per_km = f.slope, s.filter_error_intercept_m = f.intercept;
        s.odometry_error_slope_m_per_km = o.slope, s.odometry_error_intercept_m = o.intercept;
    }
    return s;
}

LocalizationResult run_localization(FlightSource& source, ParticleFilter& filter, const ProgressFn& progress, double start_x,
                                    double start_y, double start_heading_rad) {
    LocalizationResult result;
    const double mpp = filter.config().metres_per_pixel;
    FlightSample s;
    bool started = false, have_odometry = false;
    double odo_e0 = 0, odo_n0 = 0, prev_e = 0, prev_n = 0, prev_tx = 0, prev_ty = 0, distance_m = 0;
    const std::size_t hint = source.frames_hint();
    double wall_s = 0;
    while (source.next(s)) {
        const auto t0 = std::chrono::steady_clock::now();
        if (!started) {
            if (std::isnan(start_x) || std::isnan(start_y)) {
                if (!s.has_truth) throw Error("localize: the flight has no ground truth (MapX/MapY) in its first frame; give the start position (--start X,Y or --start-latlon LAT,LON)");
                start_x = s.truth_x, start_y = s.truth_y;
            }
            filter.initialise(start_x, start_y, std::isnan(start_heading_rad) ? s.heading_rad : start_heading_rad);
            prev_tx = s.truth_x, prev_ty = s.truth_y;
            started = true;
        }
        FilterInput in;
        const bool odo_ok = std::isfinite(s.odometry_east_m) && std::isfinite(s.odometry_north_m);
        if (odo_ok && !have_odometry) {  // the first good reading is the odometry's origin
            odo_e0 = prev_e = s.odometry_east_m, odo_n0 = prev_n = s.odometry_north_m;
            have_odometry = true;
        }
        in.odometry_east_m = odo_ok ? s.odometry_east_m - prev_e : NAN;
        in.odometry_north_m = odo_ok ? s.odometry_north_m - prev_n : NAN;
        if (odo_ok) prev_e = s.odometry_east_m, prev_n = s.odometry_north_m;
        in.heading_rad = s.heading_rad;
        in.frame = s.image.view();
        if (s.image.pixels.empty()) in.frame = {};
        in.map_px_per_camera_px = s.map_px_per_camera_px;
        const StepReport rep = filter.step(in);
        const double step_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        wall_s += step_s;

        LocalizationRow row;
        row.frame = s.frame_index;
        row.time_s = s.time_s;
        if (s.has_truth) {
            distance_m += std::hypot(s.truth_x - prev_tx, s.truth_y - prev_ty) * mpp;
            prev_tx = s.truth_x, prev_ty = s.truth_y;
            row.truth_x = s.truth_x, row.truth_y = s.truth_y;
        }
        row.distance_m = distance_m;
        row.odometry_x = start_x + (prev_e - odo_e0) / mpp;
        row.odometry_y = start_y - (prev_n - odo_n0) / mpp;
        row.estimate_x = rep.estimate.x, row.estimate_y = rep.estimate.y, row.estimate_yaw = rep.estimate.yaw;
        row.best_x = rep.estimate.best_x, row.best_y = rep.estimate.best_y;
        if (s.has_truth) {
            row.error_m = std::hypot(row.estimate_x - s.truth_x, row.estimate_y - s.truth_y) * mpp;
            row.odometry_error_m = std::hypot(row.odometry_x - s.truth_x, row.odometry_y - s.truth_y) * mpp;
        }
        row.particles = rep.particles, row.off_map = rep.off_map;
        row.score_ms = rep.score_ms, row.step_ms = step_s * 1000;
        row.odometry_lost = rep.odometry_lost, row.frame_missing = rep.frame_missing && !s.too_oblique, row.reinitialised = rep.reinitialised;
        row.tilt_deg = s.tilt_deg, row.too_oblique = s.too_oblique;
        row.odometry_source = s.odometry_source;
        row.lock = rep.lock;
        result.rows.push_back(row);
        if (progress) progress(result.rows.size(), hint);
    }
    result.summary = summarise(result.rows, filter.counters(), wall_s);
    return result;
}

}  // namespace trn::filter
