#include "trn/localize/localization.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "trn/detail/angles.hpp"
#include "trn/error.hpp"

namespace trn::localize {

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

BrokenLine fit_broken_line(const std::vector<double>& x, const std::vector<double>& y, double break_x) {
    if (y.size() != x.size()) return {};
    std::vector<double> xb, yb, xa, ya;
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (x[i] < break_x) xb.push_back(x[i]), yb.push_back(y[i]);
        else xa.push_back(x[i]), ya.push_back(y[i]);
    }
    return {fit_line(xb, yb), fit_line(xa, ya)};
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

double error_in_sigmas(double e, double n, double cov_nn, double cov_ne, double cov_ee) {
    const double det = cov_nn * cov_ee - cov_ne * cov_ne;
    if (!(det > 0)) return e == 0 && n == 0 ? 0 : INFINITY;
    // e' C^-1 e with C = [ee ne; ne nn] over (east, north)
    const double d2 = (cov_nn * e * e - 2 * cov_ne * e * n + cov_ee * n * n) / det;
    return std::sqrt(std::max(0.0, d2));
}

LocalizationSummary summarise(const std::vector<LocalizationRow>& rows, const filter::FilterCounters& counters, double wall_s) {
    LocalizationSummary s;
    s.steps = rows.size();
    s.counters = counters;
    if (rows.empty()) return s;
    // The filter sees a too-oblique frame as an empty one; missing means failed to load.
    for (const LocalizationRow& r : rows) s.counters.frames_missing -= r.too_oblique && s.counters.frames_missing > 0;
    std::vector<double> km, seconds, fe, oe;
    double particles = 0, score = 0;
    for (const LocalizationRow& r : rows) {
        particles += r.particles, score += r.score_ms;
        s.frames_too_oblique += r.too_oblique;
        if (std::isfinite(r.error_m) && std::isfinite(r.odometry_error_m)) {
            km.push_back(r.distance_m / 1000), fe.push_back(r.error_m), oe.push_back(r.odometry_error_m);
            seconds.push_back(r.time_s - rows.front().time_s);
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
        const BrokenLine fb = fit_broken_line(seconds, fe, kErrorSlopeBreakS), ob = fit_broken_line(seconds, oe, kErrorSlopeBreakS);
        s.filter_slope_before_break_m_per_s = fb.before.slope, s.filter_slope_after_break_m_per_s = fb.after.slope;
        s.odometry_slope_before_break_m_per_s = ob.before.slope, s.odometry_slope_after_break_m_per_s = ob.after.slope;
    }
    std::size_t judged = 0, in1 = 0, in2 = 0;
    for (const LocalizationRow& r : rows)
        if (!std::isnan(r.error_sigmas)) ++judged, in1 += r.error_sigmas <= 1, in2 += r.error_sigmas <= 2;
    if (judged) s.inside_1sigma = double(in1) / judged, s.inside_2sigma = double(in2) / judged;
    // The heading estimate.
    s.final_yaw_sd_deg = rows.back().estimate_yaw_sd / kDeg;
    double yaw_sum = 0, conv_err = 0, conv_yaw = 0;
    std::size_t yaw_n = 0, conv_n = 0, conv_yaw_n = 0;
    bool converged = false;
    // Converged: the heading and the position both confident by the run's own evidence, no truth
    // used: yaw sd below kConvergedYawSdDeg and the lock monitor's fix (yaw alone when the monitor never assessed a step).
    const bool monitored = std::any_of(rows.begin(), rows.end(), [](const LocalizationRow& r) { return !std::isnan(r.lock.drift_m); });
    for (const LocalizationRow& r : rows) {
        const double yaw_error = std::isfinite(r.truth_yaw) ? std::abs(wrap_angle(r.estimate_yaw - r.truth_yaw)) / kDeg : NAN;
        if (std::isfinite(yaw_error)) yaw_sum += yaw_error, ++yaw_n, s.final_yaw_error_deg = yaw_error;
        if (!converged && r.estimate_yaw_sd / kDeg < kConvergedYawSdDeg && (r.lock.confident || !monitored)) converged = true, s.converged_from_frame = static_cast<double>(r.frame);
        if (!converged) continue;
        if (std::isfinite(r.error_m)) conv_err += r.error_m, ++conv_n;
        if (std::isfinite(yaw_error)) conv_yaw += yaw_error, ++conv_yaw_n;
    }
    if (yaw_n) s.mean_yaw_error_deg = yaw_sum / yaw_n;
    if (conv_n) s.converged_mean_error_m = conv_err / conv_n;
    if (conv_yaw_n) s.converged_mean_yaw_error_deg = conv_yaw / conv_yaw_n;
    return s;
}

}  // namespace trn::localize
